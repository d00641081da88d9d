#!/usr/bin/python3
"""Seeds of fuzz_results_reader: results files written by `flexmbs simulate`, rewritten with
chunks of at most 8 rows (the writer's chunks are 32-64 KB each, which would make a 600 KB seed
of a five-sample run). Everything else is kept: groups, attributes with their HDF5 types
(fixed-length strings), datasets with their types, shapes, unlimited first dimensions and
Fletcher32 checksums, so `flexmbs info --verify` finds each seed intact.

    make_results_seeds.py RESULTS.h5 OUT.h5
"""
import sys

import h5py


def copy_attributes(source, target):
    for name in source.attrs:
        target.attrs.create(name, source.attrs[name], dtype=source.attrs.get_id(name).dtype)


def copy_group(source, target):
    copy_attributes(source, target)
    for name, item in source.items():
        if isinstance(item, h5py.Group):
            copy_group(item, target.create_group(name))
            continue
        chunks = None
        if item.chunks is not None:
            chunks = (min(8, max(1, item.shape[0])),) + tuple(item.chunks[1:])
        copy = target.create_dataset(name, data=item[()], dtype=item.dtype, maxshape=item.maxshape, chunks=chunks,
                                     fletcher32=item.fletcher32)
        copy_attributes(item, copy)


def main():
    source, target = sys.argv[1:3]
    with h5py.File(source, "r") as s, h5py.File(target, "w", libver="earliest") as t:
        copy_group(s, t)


if __name__ == "__main__":
    main()
