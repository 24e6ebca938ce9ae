"""The commands of a test run in one process, with no start-up cost per command: the script
reads a JSON list of argument lists on standard input and prints, as JSON, the exit code, the
standard output and the standard error of each (``python -c RUNNER``)."""

RUNNER = r"""
import contextlib, io, json, sys
import matplotlib
matplotlib.use("Agg")
from synthesis.cli import main
results = []
for argv in json.load(sys.stdin):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 2
    results.append({"argv": argv, "code": code, "stdout": out.getvalue(),
                    "stderr": err.getvalue()})
json.dump(results, sys.stdout)
"""
