"""Opens a run's run.xdmf with ParaView's XDMF reader (run with pvbatch) and checks, at every
time step, what a user would see against run.h5 and the scene:
  particles   one vertex per particle row of the frame
  boundaries  every wall and rigid body segment; each rigid body where its velocity schedule puts
              it (the integral of the schedule from 0 to t, from the resolved scene)
  mesh        (SPFEM) the frame's triangles, all counter-clockwise, covering the bodies' area less
              the half-spacing layer outside the alpha shape (within 10 %)
  surface     (SPFEM) the edges that belong to one triangle

Usage: pvbatch paraview_read_check.py RUN_DIR (sph|spfem). Exit 0 and "ok ..." when every check
passes, else exit 1 with what differs.
"""
import sys
import tomllib

import h5py
from paraview import servermanager as sm
from paraview import simple
from vtkmodules.numpy_interface import dataset_adapter as dsa


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def schedule_integral(knots, t):
    """Integral from 0 to t of a piecewise-linear [[t, vx, vy], ...] (constant outside)."""
    if not knots:
        return (0.0, 0.0)
    total = [0.0, 0.0]

    def value(s):
        if s <= knots[0][0]:
            return knots[0][1:3]
        for a, b in zip(knots, knots[1:]):
            if s <= b[0]:
                w = (s - a[0]) / (b[0] - a[0]) if b[0] > a[0] else 1.0
                return [a[1 + k] + w * (b[1 + k] - a[1 + k]) for k in range(2)]
        return knots[-1][1:3]

    # Exact for piecewise-linear: trapezoids between the knots inside [0, t].
    times = sorted({0.0, t} | {k[0] for k in knots if 0.0 < k[0] < t})
    for a, b in zip(times, times[1:]):
        va, vb = value(a), value(b)
        for k in range(2):
            total[k] += 0.5 * (va[k] + vb[k]) * (b - a)
    return tuple(total)


def main():
    run_dir, kind = sys.argv[1], sys.argv[2]
    h5 = h5py.File(f"{run_dir}/run.h5", "r")
    scene = tomllib.loads(h5["meta/scene_toml"][()].decode())
    names = h5["meta"].attrs["boundary_names"]
    names = (names.decode() if isinstance(names, bytes) else names).split("\n")
    frames = sorted(h5["frames"].keys())
    spacing = float(h5["meta"].attrs["spacing"])

    reader = simple.XDMFReader(FileNames=[f"{run_dir}/run.xdmf"])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    if len(times) != len(frames):
        fail(f"ParaView sees {len(times)} time steps, run.h5 has {len(frames)} frames")

    rigid = scene.get("rigid_body", {})
    body_area = 0.0
    for body in scene["body"].values():
        (x0, y0), (x1, y1) = body["min"], body["max"]
        # particles are cell-centred: the alpha shape lies dp/2 inside the body's outline
        body_area += (x1 - x0 - spacing) * (y1 - y0 - spacing)

    checked_rigid = 0
    for t, frame in zip(times, frames):
        g = h5["frames"][frame]
        reader.UpdatePipeline(t)
        data = sm.Fetch(reader)
        blocks = {}
        for b in range(data.GetNumberOfBlocks()):
            blocks[data.GetMetaData(b).Get(data.NAME())] = data.GetBlock(b)
        particles = blocks.get("particles")
        n = g["position"].shape[0]
        if particles is None or particles.GetNumberOfPoints() != n:
            fail(f"t = {t}: particles block missing or not {n} points")
        if abs(float(g.attrs["time"]) - t) > 1e-12 * max(1.0, t):
            fail(f"frame {frame} at {g.attrs['time']}, ParaView's step at {t}")

        lines = blocks.get("boundaries")
        if lines is None or lines.GetNumberOfCells() != g["boundary_segments"].shape[0]:
            fail(f"t = {t}: boundaries block missing or not {g['boundary_segments'].shape[0]} segments")
        lines_np = dsa.WrapDataObject(lines)
        owner = lines_np.CellData["boundary"]
        points = lines_np.Points
        for index, name in enumerate(names):
            if name not in rigid:
                continue
            shift = schedule_integral(rigid[name].get("velocity", []), t)
            expected = min(v[1] for v in rigid[name]["vertices"]) + shift[1]
            ys = [points[lines.GetCell(c).GetPointId(k)][1]
                  for c in range(lines.GetNumberOfCells()) if owner[c] == index for k in range(2)]
            if abs(min(ys) - expected) > 1e-9:
                fail(f"t = {t}: rigid body {name} bottom at {min(ys)}, its schedule says {expected}")
            checked_rigid += 1

        mesh = blocks.get("mesh")
        if kind == "sph":
            if mesh is not None:
                fail("an SPH run shows a mesh")
            continue
        if mesh is None or mesh.GetNumberOfCells() != g["triangles"].shape[0]:
            fail(f"t = {t}: mesh block missing or not {g['triangles'].shape[0]} triangles")
        mp = dsa.WrapDataObject(mesh).Points
        area = 0.0
        for c in range(mesh.GetNumberOfCells()):
            cell = mesh.GetCell(c)
            if cell.GetNumberOfPoints() != 3:
                fail(f"t = {t}: mesh cell {c} is not a triangle")
            a, b, d = (mp[cell.GetPointId(k)] for k in range(3))
            twice = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0])
            if twice <= 0.0:
                fail(f"t = {t}: mesh triangle {c} is not counter-clockwise (area {twice / 2})")
            area += 0.5 * twice
        if abs(area - body_area) > 0.1 * body_area:
            fail(f"t = {t}: mesh area {area:.4g} m^2, bodies less their layer {body_area:.4g} m^2")
        surface = blocks.get("surface")
        if surface is None or surface.GetNumberOfCells() != g["surface_edges"].shape[0]:
            fail(f"t = {t}: surface block missing or not {g['surface_edges'].shape[0]} edges")

    if rigid and checked_rigid != len(times) * len(rigid):
        fail(f"checked {checked_rigid} rigid body positions, expected {len(times) * len(rigid)}")
    print(f"ok: {len(times)} time steps, {len(names)} boundaries, {kind}")


main()
