"""viscobem: friction, true contact area and pressure of a rigid rough surface sliding over
a linear viscoelastic solid (rubber, elastomers), by a fast boundary element method.

    viscobem run [SCENE.toml | NAME] [--out DIR] [--set KEY=VALUE ...]
                                              run a study (the seed paper's by default; NAME: a
                                              built-in scene); rerun on the same DIR to resume
    viscobem scene [NAME]                     print a built-in scene (default: the template)
    viscobem bench [NAME] [--quick] --out DIR run a benchmark (NAME: all, periodic, fem,
                                              fem_convergence, fem_profile, isolated,
                                              rubber_speeds, curve,
                                              broadband, import, materials, measured, accuracy,
                                              coverage, friction_map, contact);
                                              writes only under DIR
    viscobem validate [--quick] [--case NAME ...] --out DIR   BEM vs FEM vs exact solutions

Bad input (scene or arguments) prints one line naming the problem, with no traceback,
and exits with status 2. A missing optional package costs one line naming the pip extra that
provides it, never a traceback: what a command was asked for explicitly (VTK in a scene, a Dask
scheduler, a measured topography) stops it before any work, with status 2; what is on by
default is skipped or replaced, and said so (``viscobem validate`` without pyvista writes every
report but the VTK files; the FEM without pypardiso uses SuperLU). A sweep with points that did
not converge exits with 1, and so does a validation run in which any case misses a tolerance or
a baseline.
"""

import argparse
import os
import sys
from pathlib import Path

from bem.errors import ConvergenceError, InputError

from .catalog import builtin_scenes, hint_for, missing, require, scene_path


def _cmd_run(args):
    from . import scene as scenes
    from .run.study import run_scene

    if args.workers is not None and args.workers < 1:
        raise InputError(f"--workers must be an integer >= 1, got {args.workers}")
    scene = scenes.load(args.scene, overrides=args.set)
    scheduler = args.scheduler if args.scheduler is not None else scene.scheduler
    if scheduler is not None:
        require("distributed")
    if scene.outputs["vtk"]:
        require("pyvista")
    print(f"viscobem run: {scene.title}")
    print(
        f"  surface {scene.surface.shape} on {scene.surface.length} m x {len(scene.realisations)} "
        f"realisation(s), load {', '.join(f'{x:g}' for x in scene.loads)} N, "
        f"{scene.speeds.size} speeds; writing to {args.out}"
    )
    for line in scenes.describe_xi(scene):
        print(f"  {line}")
    for text in scene.warnings:
        print(f"  WARNING: {text}")
    record = run_scene(scene, args.out, progress=not args.no_progress, scheduler=args.scheduler, workers=args.workers)
    if record.get("resumed_points"):
        print(f"  resumed: {record['resumed_points']} finished point(s) found in {args.out} were not solved again")
    if "temperature_sweep" in record:  # a sweep per temperature: the table of mu(v, T) first
        from .run.temperatures import summary

        print(summary(record))
    if "friction_curve" in record:  # a superposed study has its map only
        if "temperature_sweep" in record:
            print(f"  at {record['friction_curve_temperature']:g} K:")
        _print_curve(record["friction_curve"], record["surface"].get("hertz_radius_relaxed", [None])[0])
    for text in record["warnings"][len(scene.warnings) :]:
        print(f"  WARNING: {text}")
    print(f"  total {record['stages']['total']:.1f} s; files: {', '.join(record['files'])}")
    return 0 if record["all_converged"] else 1


def _print_curve(curve, a0=None):
    """The friction curve as a table; indenters show the contact radius and a / a0."""
    area = "a (mm)  a/a0" if a0 else "contact %"
    print(f"  {'xi':>10} {'speed (m/s)':>12} {'friction':>10} {'s.e.':>9} {area:>13} {'iters':>6}")
    for i, xi in enumerate(curve["xi"]):
        if not curve["success"][i]:
            print(f"  {xi:10.3e} {curve['speed'][i]:12.4e}  FAILED: {curve['message'][i]}")
            continue
        se = curve["friction_se"][i]
        if a0:
            a = curve["contact_radius"][i]
            contact = f"{a * 1e3:7.4f} {a / a0:5.3f}"
        else:
            contact = f"{100 * curve['contact_fraction'][i]:9.3f}"
        print(
            f"  {xi:10.3e} {curve['speed'][i]:12.4e} {curve['friction'][i]:10.5f} "
            f"{'' if se is None else f'{se:9.5f}':>9} {contact:>13} {curve['iterations'][i]:6d}"
        )


def _cmd_scene(args):
    print(scene_path(args.name).read_text(encoding="utf-8"), end="")
    return 0


def run_scene_text(text, out):
    """Run the study of a scene given as TOML text into ``out``; its record (for the benchmarks)."""
    from . import scene as scenes
    from .run.study import run_scene

    return run_scene(scenes.parse(text), out, progress=False)


def _cmd_bench(args):
    import importlib

    if args.name == "import":
        from viscobem_bench import imports

        imports.run(out_dir=args.out, repeats=1 if args.quick else 7)
        return 0
    if args.name != "all":
        module = importlib.import_module(f"viscobem_bench.{args.name}")
        module.run(quick=args.quick, out_dir=args.out)
        return 0
    from viscobem_bench import suite

    from .scene import DEFAULT_SCENE

    suite.run(quick=args.quick, out_dir=args.out, study=(run_scene_text, DEFAULT_SCENE.read_text()))
    return 0


def _optional_notes(args, names):
    """Whether to write VTK, and one line for each default part that a missing extra drops."""
    from validation.cases import CASES

    vtk = not args.no_vtk
    hint = missing("pyvista") if vtk else None
    if hint:
        print(f"  no VTK files: {hint}")
        vtk = False
    if any("fem" in CASES[n].solvers for n in names):
        hint = missing("pypardiso")
        if hint:
            print(f"  the FEM solves with SuperLU: {hint}")
    return vtk


def case_list():
    """The validation cases, one line each: name, title, and what is compared with what."""
    from validation.cases import CASES
    from validation.report import compared

    width = max(map(len, CASES))
    lines = [f"  {name:<{width}}  {c.title}\n  {'':<{width}}  ({compared(vars(c))})" for name, c in CASES.items()]
    return "validation cases (--case NAME; --quick runs each at coarse settings):\n" + "\n".join(lines) + "\n"


def _cmd_validate(args):
    if args.list:
        print(case_list(), end="")
        return 0
    from validation.report import write_reports
    from validation.runner import run_cases, select

    names = select(args.case or [])
    baseline_path, compare_with = _baseline_plan(args)
    print(f"viscobem validate: {len(names)} case(s), {'quick' if args.quick else 'full'} set; writing to {args.out}")
    vtk = _optional_notes(args, names)
    record = run_cases(
        names, quick=args.quick, out_dir=args.out, vtk=vtk, progress=not args.no_progress, jobs=args.jobs
    )
    summary = record["summary"]
    if args.sensitivity:
        from validation.sensitivity import attach

        attach(record, names, quick=args.quick, progress=not args.no_progress, jobs=args.jobs)
    comparison = None
    if compare_with:
        from validation import baselines

        comparison = baselines.compare(record, baseline_path)
    paths = write_reports(record, args.out, comparison, with_plots=not args.no_plots)
    _print_cases(record)
    status = 0 if not summary["failed"] else 1
    if args.sensitivity:
        from validation.sensitivity import print_summary

        status = print_summary(record) or status
    if comparison is not None:
        status = _print_comparison(comparison, baseline_path) or status
    if args.update_baselines:
        _update_baselines(record, baseline_path, args.out)
    print(
        f"  {summary['passed']}/{summary['cases']} cases passed in {record['seconds']:.1f} s; "
        f"reports: {', '.join(str(p) for p in paths)}"
    )
    return status


def _baseline_plan(args):
    """``(baseline path, whether to compare with it)``; bad combinations of flags are input errors."""
    from validation import baselines

    if args.update_baselines and (not args.quick or args.case):
        raise InputError(
            "--update-baselines needs --quick and every case (no --case): the baseline file holds the whole quick set"
        )
    baseline_path = args.baseline or baselines.DEFAULT
    compare_with = args.quick and not (args.update_baselines or args.no_baseline)
    if compare_with and not Path(baseline_path).exists():
        raise InputError(
            f"baseline {baseline_path} does not exist; pass --no-baseline or create it with --update-baselines"
        )
    return baseline_path, compare_with


def _print_cases(record):
    """One line per case, then the failed checks."""
    for name, case in record["cases"].items():
        judged = [k for k in case["checks"] if k["judged"]]
        print(
            f"  {name:24s} {case['status'].upper():6s} {sum(k['passed'] for k in judged):3d}/{len(judged):<3d} "
            f"checks  {case['seconds']:7.1f} s"
        )
        if case["status"] == "error":
            print(f"      {case['error']}")
    for k in record["summary"]["failed_checks"]:
        print(
            f"  FAIL {k['case']}: {k['solver']} {k['metric']} at {k['label']} = {k['value']:.3g} "
            f"> {k['tolerance']:.3g} ({k['why']})"
        )


def _print_comparison(comparison, baseline_path):
    """The regressions against the baselines; returns the exit status they give (0 or 1)."""
    for r in comparison["regressions"]:
        print(
            f"  REGRESSION {r['case']}: {r['key']} = {r['value']:.6g}, baseline {r['baseline']:.6g} "
            f"(allowed +-{r['allowed']:.3g})"
        )
    if comparison["missing"]:
        first = comparison["missing"][0]["key"]
        print(
            f"  {len(comparison['missing'])} value(s) have no baseline (first: {first}); "
            f"regenerate with: viscobem validate --quick --update-baselines --out DIR"
        )
    print(f"  baselines ({baseline_path}): " + ("match" if comparison["ok"] else "DIFFER"))
    return 0 if comparison["ok"] else 1


def _update_baselines(record, baseline_path, out):
    """Write the quick set's baselines, unless a case fails its tolerances."""
    from validation import baselines

    if record["summary"]["failed"]:
        print("  baselines NOT updated: some cases fail their tolerances")
        return
    command = "viscobem validate --quick --update-baselines"  # the output folder does not change a value
    print(f"  baselines written to {baselines.write(record, baseline_path, command)}")


def _version():
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("viscobem")
    except PackageNotFoundError:  # a source tree that is not installed
        return "unknown (not installed)"


class _Version(argparse.Action):
    """``--version``, reading the installed metadata only when asked (it is slow to import)."""

    def __init__(self, option_strings, dest, **kwargs):
        super().__init__(option_strings, dest, nargs=0, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"viscobem {_version()}")
        parser.exit()


def build_parser():
    names = ", ".join(builtin_scenes())
    parser = argparse.ArgumentParser(
        prog="viscobem",
        description=__doc__.split("\n\n")[0],
        epilog=f"built-in scenes: {names}. Start with: viscobem scene > my.toml",
    )
    parser.add_argument("--version", action=_Version, help="print the version and exit")
    parser.add_argument("-v", "--verbose", action="store_true", help="log solver progress")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser(
        "run",
        help=f"run a scene (default: the seed paper's study; built-in: {names})",
        epilog=f"built-in scenes: {names}",
    )
    run.add_argument(
        "scene", nargs="?", default=None, help=f"scene TOML file or the name of a built-in scene ({names})"
    )
    run.add_argument("--out", default="viscobem-out", help="output folder (default: viscobem-out)")
    run.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="override a scene key, e.g. --set surface.n=64 --set loading.xi.num=5 (VALUE in TOML syntax; repeatable)",
    )
    run.add_argument("--no-progress", action="store_true", help="no progress bar")
    run.add_argument("--workers", type=int, default=None, help="processes (overrides [solver] workers)")
    run.add_argument(
        "--scheduler",
        default=None,
        help="dask.distributed scheduler address, e.g. tcp://host:8786 (overrides [solver] "
        'scheduler; needs pip install "viscobem[dask]")',
    )
    run.set_defaults(func=_cmd_run)
    scene = sub.add_parser("scene", help=f"print a built-in scene ({names}; default: the template)")
    scene.add_argument("name", nargs="?", default=None, help=f"built-in scene: {names}")
    scene.set_defaults(func=_cmd_scene)
    bench = sub.add_parser("bench", help="run a benchmark (writes only under --out)")
    bench.add_argument(
        "name",
        nargs="?",
        default="all",
        choices=[
            "all",
            "periodic",
            "fem",
            "fem_convergence",
            "fem_profile",
            "isolated",
            "rubber_speeds",
            "curve",
            "broadband",
            "import",
            "materials",
            "measured",
            "accuracy",
            "coverage",
            "friction_map",
            "contact",
        ],
        help="all (default: every solver, scaling, skipping), one detailed benchmark "
        "(fem_convergence: the FEM's observed orders in mesh size, domain size and time step; "
        "fem_profile: the FEM on rough profiles over friction curves against the converged BEM, "
        "its time and memory), "
        "import (import time of bem against numpy + scipy), materials (Prony fits "
        "and master curves against pyvisco), measured (boundary treatments of measured scans: "
        "patches cut from known surfaces), accuracy (the error estimate's cost and its "
        "agreement with the twice-finer solve), coverage (the estimate against the twice-finer solve "
        "over 240 seeded cases, tuning and held out), friction_map (friction over speed and temperature from "
        "one curve, against direct solves and one curve's cost), or contact (the contact solver's "
        "mechanisms switched off in turn over a fixed case set: products, time, success, error)",
    )
    bench.add_argument("--quick", action="store_true", help="small sizes (smoke test)")
    bench.add_argument("--out", default="bench-out", help="output folder")
    bench.set_defaults(func=_cmd_bench)
    val = sub.add_parser("validate", help="run validation cases (BEM vs FEM vs exact) and write reports")
    val.add_argument("--quick", action="store_true", help="coarse settings (the CI regression set)")
    val.add_argument(
        "--case", action="append", metavar="NAME", help="run only this case (repeatable; listed below and by --list)"
    )
    val.add_argument("--list", action="store_true", help="list the validation cases and exit")
    val.add_argument("--out", default="validation-out", help="output folder (default: validation-out)")
    val.add_argument("--no-vtk", action="store_true", help="do not write VTK files")
    val.add_argument("--no-progress", action="store_true", help="no progress bar")
    val.add_argument("--no-plots", action="store_true", help="report.html without figures (faster)")
    val.add_argument(
        "--jobs",
        type=int,
        default=min(2, os.cpu_count() or 1),
        metavar="N",
        help="run N cases at a time, each in its own process with one thread (default: 2 where there are "
        "2 cores or more; 1 runs them one after another in this process)",
    )
    val.add_argument("--baseline", default=None, help="baseline file (default: validation/baselines/quick.json)")
    val.add_argument("--no-baseline", action="store_true", help="with --quick: do not compare with the baselines")
    val.add_argument(
        "--update-baselines", action="store_true", help="with --quick: store this run's numbers as the new baselines"
    )
    val.add_argument(
        "--sensitivity",
        action="store_true",
        help="rerun each case with deliberately wrong inputs (moduli, times, speed, load) and "
        "report which checks catch them (report.json['sensitivity'])",
    )
    val.set_defaults(func=_cmd_validate)
    # the case list is built only when help is shown: importing the cases costs seconds at start-up
    val.format_help = lambda: argparse.ArgumentParser.format_help(val) + "\n" + case_list()
    return parser


def main(argv=None):
    args = build_parser().parse_args(argv)
    import logging

    logging.basicConfig(
        level=logging.INFO if args.verbose else logging.WARNING, format="%(levelname)s %(name)s: %(message)s"
    )
    try:
        return args.func(args)
    except InputError as err:
        print(f"viscobem: error: {err}", file=sys.stderr)
        return 2
    except OSError as err:  # e.g. an output folder that cannot be written
        where = f" {err.filename!r}" if getattr(err, "filename", None) else ""
        print(f"viscobem: error: cannot write{where}: {err.strerror or err}", file=sys.stderr)
        return 2
    except ImportError as err:  # an optional package: one line naming its extra
        hint = hint_for(err)
        if hint is None:
            raise
        print(f"viscobem: error: {hint}", file=sys.stderr)
        return 2
    except ConvergenceError as err:
        print(f"viscobem: did not converge: {err}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("viscobem: interrupted; the finished points are kept: rerun the same command to resume", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
