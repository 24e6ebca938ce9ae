"""``assur analyze TABLE.yaml``: kinematic analysis of a mechanism over the input cycle.

Reads a chain table with a ``geometry:`` sketch or an identification table with ``params:``,
solves the groups in layering order at ``--points`` positions and prints a summary: the
existence verdict of every group (with the intervals where it cannot be assembled), the
ranges of the outputs, the largest pressure angle and the swing of every revolute joint.
``--json`` prints every position instead; ``--csv``, ``--plot`` and ``--animate`` write files.
"""

from __future__ import annotations

import argparse
import json
import sys

from assur import atomic_write_text, save_animation_gif, save_mechanism_png
from assur.text import languages, render
from synthesis.app.analysis import analyse_table
from synthesis.app.analysis_csv import analysis_csv
from synthesis.app.analysis_json import analysis_record
from synthesis.app.analysis_text import analysis_text

NAME = "analyze"
HELP = "kinematic analysis over the crank cycle: positions, analogs, existence of groups"
ORDER = 20


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``assur analyze``."""
    parser.add_argument("table", help="chain table with a geometry: sketch, or an "
                                      "identification table with params:")
    parser.add_argument("--points", type=int, default=360,
                        help="number of analysed positions (default 360)")
    parser.add_argument("--json", action="store_true",
                        help="print every position as JSON instead of the summary")
    parser.add_argument("--csv", metavar="FILE", help="write one row per position")
    parser.add_argument("--plot", metavar="FILE.png",
                        help="draw the mechanism at --at with the traced paths")
    parser.add_argument("--at", type=float, default=0.0,
                        help="crank angle φ (degrees; actuator: length in mm) drawn by --plot "
                             "(default: the first position)")
    parser.add_argument("--animate", metavar="FILE.gif", help="animate a whole cycle")
    parser.add_argument("--frames", type=int, default=48, help="frames of --animate (48)")
    parser.add_argument("--omega", type=float, default=None,
                        help="input speed (rad/s of the crank, mm/s of an actuator): add "
                             "velocities and accelerations to --json and --csv")
    parser.add_argument("--lang", choices=languages(), default="en", help="report language")


def run(args: argparse.Namespace) -> int:
    """Analyse the table and report."""
    result = analyse_table(args.table, points=args.points, omega=args.omega)
    if args.json:
        json.dump(analysis_record(result), sys.stdout, ensure_ascii=False)
        sys.stdout.write("\n")
    else:
        print(analysis_text(result, args.lang))
    notes = sys.stderr if args.json else sys.stdout
    if args.csv:
        atomic_write_text(args.csv, analysis_csv(result))
        print(render("analyze.written", args.lang, path=args.csv), file=notes)
    if args.plot:
        save_mechanism_png(result.motion, args.plot, index=result.index_at(args.at),
                           lang=args.lang)
        print(render("analyze.written", args.lang, path=args.plot), file=notes)
    if args.animate:
        save_animation_gif(result.motion, args.animate, frames=args.frames, lang=args.lang)
        print(render("analyze.written", args.lang, path=args.animate), file=notes)
    return 0
