"""The coursework report: ``assur report TABLE.yaml`` writes one self-contained HTML page.

:func:`build_report` assesses a table (:func:`synthesis.app.assess.assess`: structure,
identification table, existence; for a synthesis problem the synthesis first) and collects
the sections with their schemes and diagrams; :func:`render_html` turns the result into the
page; :func:`write_report` does both and writes the file.
"""

from synthesis.app.coursework.report import (
    CourseworkReport,
    build_report,
    render_html,
    write_report,
)

__all__ = ["CourseworkReport", "build_report", "render_html", "write_report"]
