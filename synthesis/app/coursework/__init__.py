"""The coursework report: ``assur report TABLE.yaml`` writes one self-contained HTML page.

:func:`build_report` analyses a table (structure, identification table, schemes, existence,
kinematics, synthesis) and :func:`render_html` turns the result into the page;
:func:`write_report` does both and writes the file.
"""

from synthesis.app.coursework.report import (
    CourseworkReport,
    build_report,
    is_problem,
    render_html,
    write_report,
)

__all__ = ["CourseworkReport", "build_report", "is_problem", "render_html", "write_report"]
