#!/usr/bin/python3
"""Keep every k-th frame of a flow file (a coarser stored frame interval of the same flow),
and optionally round its fields to fewer significant bits (a known, tiny perturbation).

    subsample_flow.py IN.nc K OUT.nc [--keep-bits N]

Frames 0, K, 2K, ... of every variable whose first dimension is `time` are kept; all
other variables (bed, summary maps, gauge records), every attribute, and each variable's
chunking, shuffle and deflate settings are copied as they are, so the output is the flow
file flotsam hydro would have written at K times the output interval (same flow, same
storage), and its size is comparable. The history attribute records the subsampling.
Written to OUT.part and renamed.

--keep-bits N stores the (time, y, x) fields (h, u, v) with netCDF-C's BitRound
quantisation: each value keeps N significant bits of its mantissa (1 <= N <= 23), so it
moves by at most 2^-(N+1) of itself; zero stays zero, a depth keeps its sign, and a wet
cell stays wet. K = 1 keeps every frame. Two uses (docs/studies/resolution_by_debris.md, "How much of that is
chaos?"): a perturbation of known size, to measure how far the debris answer moves when
the flow barely changes; and smaller files that inflate faster (the low bits become
zeros).
"""
import os
import sys

import netCDF4


def copy_variable(src, dst, name, k, keep_bits=None):
    v = src.variables[name]
    dims = v.dimensions
    kwargs = {}
    if keep_bits is not None and dims == ("time", "y", "x") and v.dtype.kind == "f":
        kwargs.update(significant_digits=keep_bits, quantize_mode="BitRound")
    if v.chunking() != "contiguous":
        kwargs["chunksizes"] = v.chunking()
    filters = v.filters() or {}
    if filters.get("zlib"):
        kwargs.update(zlib=True, complevel=filters.get("complevel", 1), shuffle=filters.get("shuffle", False))
    attrs = {a: v.getncattr(a) for a in v.ncattrs()}
    fill = attrs.pop("_FillValue", None)
    out = dst.createVariable(name, v.datatype, dims, fill_value=fill, **kwargs)
    out.setncatts(attrs)
    v.set_auto_maskandscale(False)
    out.set_auto_maskandscale(False)
    if dims and dims[0] == "time":
        for j, i in enumerate(range(0, len(src.dimensions["time"]), k)):
            out[j] = v[i]
    else:
        out[...] = v[...]


def main(argv):
    keep_bits = None
    if len(argv) == 6 and argv[4] == "--keep-bits":
        try:
            keep_bits = int(argv[5])
        except ValueError:
            sys.exit(f"subsample_flow.py: --keep-bits must be a whole number, got {argv[5]!r}")
        if not 1 <= keep_bits <= 23:
            sys.exit(f"subsample_flow.py: --keep-bits must be 1 to 23 (a float's mantissa bits), got {keep_bits}")
        argv = argv[:4]
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    path_in, k, path_out = argv[1], int(argv[2]), argv[3]
    if k < 1:
        sys.exit(f"subsample_flow.py: K must be at least 1, got {k}")
    part = path_out + ".part"
    with netCDF4.Dataset(path_in) as src, netCDF4.Dataset(part, "w", format=src.data_model) as dst:
        if "time" not in src.dimensions:
            sys.exit(f"subsample_flow.py: {path_in}: no dimension 'time' (not a flow file)")
        n = len(src.dimensions["time"])
        for name, d in src.dimensions.items():
            size = (n + k - 1) // k if name == "time" else len(d)
            dst.createDimension(name, None if d.isunlimited() else size)
        attrs = {a: src.getncattr(a) for a in src.ncattrs()}
        what = f"every {k}th frame" + (f", h u v kept to {keep_bits} significant bits (BitRound)" if keep_bits else "")
        attrs["history"] = attrs.get("history", "") + f"\nsubsample_flow.py: {what} of {os.path.basename(path_in)}"
        dst.setncatts(attrs)
        for name in src.variables:
            copy_variable(src, dst, name, k, keep_bits)
    os.replace(part, path_out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
