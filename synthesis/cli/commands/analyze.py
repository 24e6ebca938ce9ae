"""``assur analyze TABLE.yaml``: kinematic analysis of a mechanism over the input cycle.

Reads a chain table with a ``geometry:`` sketch or an identification table with ``params:``,
solves the groups in layering order at ``--points`` positions and prints a summary: the
existence verdict of every group (with the intervals where it cannot be assembled), the
ranges of the outputs, the largest pressure angle and the swing of every revolute joint.
``--json`` prints every position instead; ``--csv``, ``--plot``, ``--animate`` and
``--modes-plot`` (the assembly modes of triads and class IV groups) write files.
``--forces --omega W`` adds the force analysis (``docs/forces.md``) to each of them.
"""

from __future__ import annotations

import argparse

from assur.text import DEFAULT, languages, render

#: The output options, checked before the run.
OUTPUTS = {"csv": "file", "plot": "file", "animate": "file", "modes_plot": "file"}


def add_args(parser: argparse.ArgumentParser, lang: str = DEFAULT) -> None:
    """Options of ``assur analyze``."""
    parser.add_argument("table", help=render("cli.analyze.table", lang))
    parser.add_argument("--points", type=int, default=360, help=render("cli.analyze.points", lang))
    parser.add_argument("--json", action="store_true", help=render("cli.analyze.json", lang))
    parser.add_argument("--csv", metavar="FILE", help=render("cli.analyze.csv", lang))
    parser.add_argument("--plot", metavar="FILE.png|svg|pdf|jpg", help=render("cli.analyze.plot", lang))
    parser.add_argument("--at", type=float, default=0.0, help=render("cli.analyze.at", lang))
    parser.add_argument("--animate", metavar="FILE.gif|mp4", help=render("cli.analyze.animate", lang))
    parser.add_argument("--modes-plot", metavar="FILE.png", help=render("higher.cli.modes_plot", lang))
    parser.add_argument("--frames", type=int, default=48, help=render("cli.analyze.frames", lang))
    parser.add_argument("--omega", type=float, default=None, help=render("cli.analyze.omega", lang))
    parser.add_argument("--forces", action="store_true", help=render("force.cli.forces", lang))
    parser.add_argument("--lang", choices=languages(), default=lang,
                        help=render("cli.analyze.lang", lang))


def run(args: argparse.Namespace) -> int:
    """Analyse the table and report (what a run does not ask for is never imported)."""
    from assur.api import MIN_POINTS, analyse
    from assur.plot.formats import animation_format, picture_format
    from synthesis.app.analysis_text import analysis_text
    from synthesis.app.outputs import outputs_of, stdout_taken
    from synthesis.app.strict_json import strict_json
    from synthesis.app.table_warnings import print_warnings
    from synthesis.cli.options import AT, FRAMES, OMEGA, check_ranges, points_range

    check_ranges(args, {"points": points_range(MIN_POINTS), "omega": OMEGA, "at": AT,
                        "frames": FRAMES})
    csv_alone = stdout_taken(args, "csv")
    if args.plot:  # a format that cannot be written is refused before any work
        picture_format(args.plot)
    if args.animate:
        animation_format(args.animate)
    result = analyse(args.table, points=args.points, forces=args.forces, omega=args.omega)
    forces = result.forces
    if args.json:
        print(strict_json(result.to_dict()))
    else:
        print_warnings(result.warnings, args.table, args.lang)
        if not csv_alone:
            print(analysis_text(result, args.lang))
            if forces is not None:
                from synthesis.app.analysis_forces_render import forces_text

                print("\n" + forces_text(result, forces, args.lang))
    outputs = outputs_of(args)
    table = None  # the CSV is written last: a run that fails while drawing leaves none
    if args.csv:
        from synthesis.app.analysis_csv import analysis_csv
        from synthesis.app.analysis_forces_render import forces_columns

        table = analysis_csv(result, forces_columns(forces) if forces is not None else [])
    if args.plot:
        from assur.plot.mechanism import save_mechanism_picture
        from synthesis.app.analysis_forces_plot import save_forces_png

        index = result.index_at(args.at)
        outputs.write(args.plot, lambda path: save_mechanism_picture(
            result.motion, path, index=index, lang=args.lang) if forces is None
            else save_forces_png(result, forces, path, index=index, lang=args.lang))
    if args.animate:
        from assur.plot.mechanism import save_animation

        outputs.write(args.animate, lambda path: save_animation(
            result.motion, path, frames=args.frames, lang=args.lang))
    if args.modes_plot:
        from assur.plot.modes import save_modes_png

        outputs.write(args.modes_plot, lambda path: save_modes_png(
            result.motion, path, index=result.index_at(0.0), lang=args.lang))
    if table is not None:
        outputs.write_text(args.csv, table)
    return 0
