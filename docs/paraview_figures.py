"""The screenshots of docs/paraview.md, rendered from the validation's own VTK files.

    python docs/paraview_figures.py [VALIDATION_OUT]

It runs the built-in ``sphere`` scene at three speeds with VTK output (``viscobem run sphere``)
and, unless ``VALIDATION_OUT`` names the folder of a ``viscobem validate`` run that holds the
case ``cylinder_sls_r3``, that case at quick settings, into a temporary folder; then it renders
their VTK files off screen (pyvista, the ``vtk`` extra; no display and no ParaView needed) into
``docs/figures/paraview_*.png``. The documentation build only shows the committed PNGs: it
never runs this script.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

FIGURES = Path(__file__).resolve().parent / "figures"
CASE = "cylinder_sls_r3"
SPHERE = ["run", "sphere", "--no-progress", "--set", "outputs.vtk=true", "--set", "outputs.plots=false"]
SPHERE += ["--set", "loading.xi.num=3"]  # xi = 1e-3, 0.32 (near the friction peak), 100


def _label(grid):
    fd = grid.field_data
    speed = f"V = {float(fd['speed'][0]):.3g} m/s"
    if "xi" in fd:
        speed += f", xi = {float(fd['xi'][0]):.3g}"
    return f"{speed}: friction {float(fd['friction'][0]):.3g}"


def bem_sphere(run, path):
    """Pressure under the sliding sphere at the slowest speed and near the friction peak."""
    import pyvista as pv

    files = sorted((run / "vtk").glob("point_*.vti"))
    grids = [pv.read(files[0]), pv.read(files[1])]
    top = max(float(g.point_data["pressure"].max()) for g in grids) / 1e6
    plotter = pv.Plotter(shape=(1, 2), off_screen=True, window_size=(1400, 640), border=False)
    for k, grid in enumerate(grids):
        plotter.subplot(0, k)
        grid = grid.copy()
        grid.point_data["pressure (MPa)"] = grid.point_data["pressure"] / 1e6
        plotter.add_mesh(
            grid,
            scalars="pressure (MPa)",
            cmap="magma",
            clim=(0, top),
            show_scalar_bar=k == 1,
            scalar_bar_args={"title": "p (MPa)", "vertical": True, "color": "black", "position_x": 0.86, "width": 0.06},
        )
        plotter.add_mesh(grid.contour([0.5], scalars="contact"), color="cyan", line_width=3)
        plotter.add_text(_label(grid), font_size=11)
        plotter.view_xy()
        plotter.camera.zoom(1.1)
    plotter.screenshot(path)
    plotter.close()


def fem_cylinder(out, path):
    """Von Mises stress at the nodes under the rolling cylinder, near the contact (FEM)."""
    import numpy as np
    import pyvista as pv

    folder = out / "vtk" / CASE / "fem"
    blocks = pv.read(sorted(folder.glob("point_*.vtm"))[-1])
    volume, interface = blocks["volume"], blocks["interface"]
    width = float(np.ptp(interface.points[:, 0]))
    near = volume.clip_box((-1.5 * width, 1.5 * width, -1.2 * width, 0.01 * width, -1, 1), invert=False)
    near.point_data["von Mises (MPa)"] = near.point_data["von_mises_nodal"] / 1e6
    plotter = pv.Plotter(off_screen=True, window_size=(1400, 700))
    plotter.add_mesh(
        near,
        scalars="von Mises (MPa)",
        cmap="viridis",
        show_edges=True,
        edge_color="#555555",
        scalar_bar_args={"title": "von Mises, nodal (MPa)", "color": "black"},
    )
    plotter.add_text(_label(volume) + "  (the cylinder rolls toward +x)", font_size=11)
    plotter.view_xy()
    plotter.camera.zoom(1.3)
    plotter.screenshot(path)
    plotter.close()


def _viscobem(*args):
    subprocess.run([sys.executable, "-m", "viscobem_cli.main", *args], check=True)


def main(argv=None):
    args = list(sys.argv[1:] if argv is None else argv)
    FIGURES.mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        _viscobem(*SPHERE, "--out", str(Path(tmp) / "sphere"))
        out = Path(args[0]) if args else Path(tmp) / "validation"
        if not args:
            _viscobem(
                "validate", "--quick", "--no-progress", "--no-plots", "--no-baseline", "--case", CASE, "--out", str(out)
            )
        bem_sphere(Path(tmp) / "sphere", FIGURES / "paraview_bem_sphere.png")
        fem_cylinder(out, FIGURES / "paraview_fem_cylinder.png")
    print(f"wrote {FIGURES / 'paraview_bem_sphere.png'} and {FIGURES / 'paraview_fem_cylinder.png'}")


if __name__ == "__main__":
    main()
