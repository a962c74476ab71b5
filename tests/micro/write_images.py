#!/usr/bin/python3
"""Writes small voxel images with writers independent of lamina (h5py, numpy,
and VTK XML laid out by hand with Python's base64, struct and zlib) for
tests/micro/image_io_test.cpp.

The pattern: the voxel (i, j, k) (x, y, z) holds ID[(i + 2 j + 3 k) % 3] with
ID = (0, 7, 9), on a 5 x 4 x 3 grid (distinct sizes expose an axis mix-up).
Usage: write_images.py OUT_DIR
"""
import base64
import os
import struct
import sys
import zlib

import h5py
import numpy as np

NX, NY, NZ = 5, 4, 3
ID = (0, 7, 9)


def pattern():
    a = np.zeros((NX, NY, NZ), dtype=np.int64)  # indexed [x, y, z]
    for i in range(NX):
        for j in range(NY):
            for k in range(NZ):
                a[i, j, k] = ID[(i + 2 * j + 3 * k) % 3]
    return a


def x_fastest_bytes(a, fmt):
    """The values with x fastest (VTK order) packed with struct format fmt."""
    vals = [int(a[i, j, k]) for k in range(NZ) for j in range(NY) for i in range(NX)]
    return struct.pack(fmt[0] + str(len(vals)) + fmt[1:], *vals)


def vti(path, data_array, appended=None, header_type="UInt32", compressor=None,
        byte_order="LittleEndian", cell=True):
    ext = "0 %d 0 %d 0 %d" % ((NX, NY, NZ) if cell else (NX - 1, NY - 1, NZ - 1))
    section = "CellData" if cell else "PointData"
    comp = ' compressor="%s"' % compressor if compressor else ""
    head = ('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="1.0" byte_order="%s" '
            'header_type="%s"%s>\n<ImageData WholeExtent="%s" Origin="0 0 0" Spacing="0.5 0.5 2">\n'
            '<Piece Extent="%s">\n<%s Scalars="labels">\n%s\n</%s>\n</Piece>\n</ImageData>\n'
            % (byte_order, header_type, comp, ext, ext, section, data_array, section))
    with open(path, "wb") as f:
        f.write(head.encode())
        if appended is not None:
            f.write(b'<AppendedData encoding="raw">\n  _' + appended + b"\n</AppendedData>\n")
        f.write(b"</VTKFile>\n")


def main():
    out = sys.argv[1]
    a = pattern()
    # HDF5 through h5py: lamina's axis order (a[x, y, z]) and the zyx order of scanners
    with h5py.File(os.path.join(out, "scan.h5"), "w") as f:
        f.create_dataset("/scan/labels", data=a.astype(np.uint16))
        f.create_dataset("/scan/zyx", data=np.ascontiguousarray(a.transpose(2, 1, 0)).astype(np.int8))
        f.create_dataset("/scan/float", data=a.astype(np.float32))
    # a huge, never written (chunked, so the file stays small) dataset for the memory check
    with h5py.File(os.path.join(out, "huge.h5"), "w") as f:
        f.create_dataset("/labels", shape=(8192, 8192, 8192), dtype=np.uint8, chunks=(64, 64, 64))
    # raw: big-endian int16, x fastest, after a 16-byte header
    with open(os.path.join(out, "scan.raw"), "wb") as f:
        f.write(b"H" * 16 + x_fastest_bytes(a, ">h"))

    ascii_vals = " ".join(str(int(a[i, j, k])) for k in range(NZ) for j in range(NY) for i in range(NX))
    vti(os.path.join(out, "ascii.vti"),
        '<DataArray type="UInt8" Name="labels" format="ascii">\n%s\n</DataArray>' % ascii_vals)
    vti(os.path.join(out, "point.vti"),
        '<DataArray type="Int16" Name="labels" format="ascii">%s</DataArray>' % ascii_vals, cell=False)
    # inline binary, uncompressed: base64 of [UInt32 byte count][Int32 data] in one stream
    data = x_fastest_bytes(a, "<i")
    b64 = base64.b64encode(struct.pack("<I", len(data)) + data).decode()
    vti(os.path.join(out, "binary.vti"),
        '<DataArray type="Int32" Name="labels" format="binary">\n%s\n</DataArray>' % b64)
    # appended raw, big endian, UInt64 header, UInt16 data
    data = x_fastest_bytes(a, ">H")
    vti(os.path.join(out, "appended.vti"),
        '<DataArray type="UInt16" Name="labels" format="appended" offset="0"/>',
        appended=struct.pack(">Q", len(data)) + data, header_type="UInt64", byte_order="BigEndian")
    # zlib, inline binary: header [blocks, block size, last size, compressed sizes]
    # and the blocks base64-encoded as two separate streams (as VTK writes them);
    # 16-byte blocks so that there are several
    data = x_fastest_bytes(a, "<i")
    bs = 16
    blocks = [zlib.compress(data[o:o + bs]) for o in range(0, len(data), bs)]
    last = len(data) - (len(blocks) - 1) * bs
    header = struct.pack("<%dI" % (3 + len(blocks)), len(blocks), bs, last, *[len(b) for b in blocks])
    b64 = base64.b64encode(header).decode() + base64.b64encode(b"".join(blocks)).decode()
    vti(os.path.join(out, "zlib.vti"),
        '<DataArray type="Int32" Name="labels" format="binary">%s</DataArray>' % b64,
        compressor="vtkZLibDataCompressor")
    # zlib, appended raw, a second array before ours (offsets count from the '_')
    other = struct.pack("<I", 4) + struct.pack("<f", 1.0)
    raw = header + b"".join(blocks)
    vti(os.path.join(out, "zlib-appended.vti"),
        '<DataArray type="Float32" Name="other" format="appended" offset="0"/>\n'
        '<DataArray type="Int32" Name="labels" format="appended" offset="%d"/>' % len(other),
        appended=other + raw, compressor="vtkZLibDataCompressor")
    # truncated appended data: the array claims more bytes than the file holds
    data = x_fastest_bytes(a, "<i")
    vti(os.path.join(out, "truncated.vti"),
        '<DataArray type="Int32" Name="labels" format="appended" offset="0"/>',
        appended=struct.pack("<I", len(data)) + data[: len(data) // 2])


if __name__ == "__main__":
    main()
