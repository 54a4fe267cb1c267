"""What limits the time step of a nested run, and how wet it is
(docs/studies/hydro_speed_levers.md). Reads what a run leaves; runs nothing.

  flow_dt_limits.py frames FLOW.nc [EVERY]
      per EVERY-th stored frame (window only): wet fraction, and the cell that sets the
      CFL step over the whole window and over the city (x >= 0) alone
  flow_dt_limits.py checkpoint CKPT.nc NX_COARSE NY_COARSE DX_COARSE X0_COARSE NX_FINE NY_FINE DX_FINE X0_FINE
      the exact state of both grids at a checkpoint: each grid's limiting cell
      (X0: the west edge of the grid [m]; the fine grid starts at the nesting interface)

The step is the solver's: dt = cfl / ((|u| + c) / dx + (|v| + c) / dy), c = sqrt(g h),
cfl = 0.8 (FiniteVolumeDef's default, --cfl), over cells deeper than the dry tolerance
1e-9 m (PhysicsDef's, --dry-depth). The two wet shares printed use 1e-9 m and 1 mm.
"""
import sys

import numpy as np
from netCDF4 import Dataset

G, CFL, DRY = 9.81, 0.8, 1e-9


def rates(h, u, v, dx):
    wet = h > DRY
    c = np.sqrt(G * np.maximum(h, 0.0))
    return np.where(wet, (np.abs(u) + c) / dx + (np.abs(v) + c) / dx, 0.0), wet


def limit(a, h, u, v, xs, ys):
    j, i = np.unravel_index(np.argmax(a), a.shape)
    return (f"{CFL / a[j, i] * 1e3:.3f} ms at ({xs[i]:.2f}, {ys[j]:.2f}) "
            f"h={h[j, i]:.3f} |u|={abs(u[j, i]):.2f} |v|={abs(v[j, i]):.2f}")


def frames(path, every):
    f = Dataset(path)
    x, y, t = f["x"][:], f["y"][:], f["time"][:]
    dx = float(x[1] - x[0])
    land = f["z"][:].astype(float) > 0.0
    city = np.broadcast_to(x >= 0.0, land.shape)
    print(f"# {path}: window {len(x)} x {len(y)} cells of {dx:.3g} m")
    print("# t [s] | wet % (h > 1e-9) | wet % (h > 1 mm) | land wet % (h > 1 mm) | dt over the window | dt over the city (x >= 0)")
    for k in range(len(t)):
        if k % every and k != len(t) - 1:
            continue
        h, u, v = (f[n][k].astype(float).filled(0.0) for n in ("h", "u", "v"))
        a, wet = rates(h, u, v, dx)
        if not wet.any():  # a stopped run's file: frames not written yet
            break
        print(f"{t[k]:6.1f} | {100 * wet.mean():5.1f} | {100 * (h > 1e-3).mean():5.1f} | {100 * (h[land] > 1e-3).mean():5.1f} | "
              f"{limit(a, h, u, v, x, y)} | {limit(np.where(city, a, 0.0), h, u, v, x, y)}")


def checkpoint(path, grids):
    f = Dataset(path)
    print(f"# {path}: t = {f.getncattr('time')} s, {int(f.getncattr('steps'))} (coarse) steps")
    for k, (nx, ny, dx, x0) in enumerate(grids):
        h, hu, hv = (f[f"state_{3 * k + q}"][:].reshape(ny + 4, nx + 4)[2:-2, 2:-2] for q in range(3))  # 2 ghost cells
        u = np.where(h > DRY, hu / np.maximum(h, DRY), 0.0)
        v = np.where(h > DRY, hv / np.maximum(h, DRY), 0.0)
        a, wet = rates(h, u, v, dx)
        xs = x0 + (np.arange(nx) + 0.5) * dx
        ys = np.arange(ny) + 0.5  # row numbers (south to north)
        print(f"grid {k} ({nx} x {ny} cells of {dx} m, wet {100 * wet.mean():.1f} %): {limit(a, h, u, v, xs, ys)}")
        for cut in (-0.6, 0.0):
            if xs[0] < cut < xs[-1]:
                print(f"  east of x = {cut}: {limit(np.where(xs >= cut, a, 0.0), h, u, v, xs, ys)}")


if __name__ == "__main__":
    if len(sys.argv) >= 3 and sys.argv[1] == "frames":
        frames(sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 1)
    elif len(sys.argv) == 11 and sys.argv[1] == "checkpoint":
        a = sys.argv[3:]
        frames_of = [(int(a[0]), int(a[1]), float(a[2]), float(a[3])), (int(a[4]), int(a[5]), float(a[6]), float(a[7]))]
        checkpoint(sys.argv[2], frames_of)
    else:
        sys.exit(__doc__)
