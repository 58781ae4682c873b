"""``viscobem`` command line.

    viscobem run [SCENE.toml | NAME] [--out DIR] [--workers N] [--scheduler ADDR]
                                              run a study (the seed paper's by default;
                                              NAME: a built-in scene, e.g. seed_figures);
                                              rerun on the same DIR to resume a sweep
    viscobem bench [--quick] --out DIR        run time against error of every solver, scaling,
                                              skipping; regenerates README's bench table
    viscobem bench periodic|fem|isolated [--quick] --out DIR   one solver's detailed benchmark
    viscobem scene                            print the built-in default scene

Bad input (scene or arguments) prints one line naming the problem, with no traceback,
and exits with status 2; a sweep with points that did not converge exits with 1.
"""
import argparse
import logging
import sys

from bem.errors import ConvergenceError, InputError


def _cmd_run(args):
    from . import scene as scenes
    from .study import run_scene

    scene = scenes.load(args.scene)
    if args.workers is not None and args.workers < 1:
        raise InputError(f"--workers must be an integer >= 1, got {args.workers}")
    print(f"viscobem run: {scene.title}")
    print(f"  surface {scene.surface.shape} on {scene.surface.length} m x {len(scene.realisations)} "
          f"realisation(s), load {', '.join(f'{x:g}' for x in scene.loads)} N, "
          f"{scene.speeds.size} speeds; writing to {args.out}")
    record = run_scene(scene, args.out, progress=not args.no_progress, scheduler=args.scheduler,
                       workers=args.workers)
    if record["resumed_points"]:
        print(f"  resumed: {record['resumed_points']} finished point(s) found in {args.out} were not solved again")
    curve = record["friction_curve"]
    print(f"  {'xi':>10} {'speed (m/s)':>12} {'friction':>10} {'s.e.':>9} {'contact':>9} {'iters':>6}")
    for i, xi in enumerate(curve["xi"]):
        if curve["success"][i]:
            se = curve["friction_se"][i]
            print(f"  {xi:10.3e} {curve['speed'][i]:12.4e} {curve['friction'][i]:10.5f} "
                  f"{'' if se is None else f'{se:9.5f}':>9} {curve['contact_fraction'][i]:9.4f} "
                  f"{curve['iterations'][i]:6d}")
        else:
            print(f"  {xi:10.3e} {curve['speed'][i]:12.4e}  FAILED: {curve['message'][i]}")
    print(f"  total {record['stages']['total']:.1f} s; files: {', '.join(record['files'])}")
    return 0 if record["all_converged"] else 1


def _cmd_scene(args):
    from .scene import DEFAULT_SCENE

    print(DEFAULT_SCENE.read_text(), end="")
    return 0


def _cmd_bench(args):
    import importlib
    from pathlib import Path

    if args.name != "all":
        module = importlib.import_module(f"benchmarks.{args.name}")
        module.run(quick=args.quick, out_dir=args.out)
        return 0
    from benchmarks import suite

    readme = None
    if not args.no_readme:
        readme = Path(args.readme) if args.readme else Path(suite.__file__).resolve().parents[1] / "README.md"
        if not readme.is_file():
            print(f"viscobem bench: no README at {readme}; the table is only in {args.out}/bench.md")
            readme = None
    suite.run(quick=args.quick, out_dir=args.out, readme=readme)
    return 0


def build_parser():
    parser = argparse.ArgumentParser(prog="viscobem", description=__doc__.split("\n\n")[0])
    parser.add_argument("-v", "--verbose", action="store_true", help="log solver progress")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run a scene (default: the seed paper's study)")
    run.add_argument("scene", nargs="?", default=None,
                     help="scene TOML file or the name of a built-in scene (seed, seed_figures)")
    run.add_argument("--out", default="viscobem-out", help="output folder (default: viscobem-out)")
    run.add_argument("--no-progress", action="store_true", help="no progress bar")
    run.add_argument("--workers", type=int, default=None, help="processes (overrides [solver] workers)")
    run.add_argument("--scheduler", default=None,
                     help="dask.distributed scheduler address, e.g. tcp://host:8786 (overrides [solver] scheduler)")
    run.set_defaults(func=_cmd_run)
    scene = sub.add_parser("scene", help="print the built-in default scene (a template)")
    scene.set_defaults(func=_cmd_scene)
    bench = sub.add_parser("bench", help="run a benchmark")
    bench.add_argument("name", nargs="?", default="all", choices=["all", "periodic", "fem", "isolated"],
                       help="all (default: every solver, scaling, skipping) or one detailed benchmark")
    bench.add_argument("--readme", default=None, help="README whose bench table to regenerate "
                       "(default: the project's README.md)")
    bench.add_argument("--no-readme", action="store_true", help="leave the README alone")
    bench.add_argument("--quick", action="store_true", help="small sizes (smoke test)")
    bench.add_argument("--out", default="bench-out", help="output folder")
    bench.set_defaults(func=_cmd_bench)
    return parser


def main(argv=None):
    args = build_parser().parse_args(argv)
    logging.basicConfig(level=logging.INFO if args.verbose else logging.WARNING,
                        format="%(levelname)s %(name)s: %(message)s")
    try:
        return args.func(args)
    except InputError as err:
        print(f"viscobem: error: {err}", file=sys.stderr)
        return 2
    except OSError as err:  # e.g. an output folder that cannot be written
        where = f" {err.filename!r}" if getattr(err, "filename", None) else ""
        print(f"viscobem: error: cannot write{where}: {err.strerror or err}", file=sys.stderr)
        return 2
    except ConvergenceError as err:
        print(f"viscobem: did not converge: {err}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("viscobem: interrupted; finished points are in results.json", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
