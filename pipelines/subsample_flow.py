#!/usr/bin/python3
"""Keep every k-th frame of a flow file (a coarser stored frame interval of the same flow).

    subsample_flow.py IN.nc K OUT.nc

Frames 0, K, 2K, ... of every variable whose first dimension is `time` are kept; all
other variables (bed, summary maps, gauge records), every attribute, and each variable's
chunking, shuffle and deflate settings are copied as they are, so the output is the flow
file flotsam hydro would have written at K times the output interval (same flow, same
storage), and its size is comparable. The history attribute records the subsampling.
Written to OUT.part and renamed.
"""
import os
import sys

import netCDF4


def copy_variable(src, dst, name, k):
    v = src.variables[name]
    dims = v.dimensions
    kwargs = {}
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
        attrs["history"] = attrs.get("history", "") + f"\nsubsample_flow.py: every {k}th frame of {os.path.basename(path_in)}"
        dst.setncatts(attrs)
        for name in src.variables:
            copy_variable(src, dst, name, k)
    os.replace(part, path_out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
