"""Writes hand-made particle outputs as scarp writes them (particles.pvd,
particles_NNNNN.pvtu and its .vtu pieces: Float32 arrays, zlib-compressed
binary with UInt32 block headers, as deal.II 9.4 writes them), so that the
figure and table tools can be tested on points of known values. The reader,
tools/read_particles.py, is checked against deal.II's own files by the test
postprocess_particle_vtu_writer.

A point is a dict: x, y and any scalar field by name ("velocity_0",
"F_01", ...); a field named NAME_0, NAME_1, NAME_2 is written as a
3-component vector NAME, as deal.II writes vectors.
"""
import base64
import os
import struct
import zlib


def _binary(values, code):
    raw = struct.pack("<%d%s" % (len(values), code), *values)
    packed = zlib.compress(raw)
    header = struct.pack("<4I", 1, len(raw), len(raw), len(packed))
    return (base64.b64encode(header) + base64.b64encode(packed)).decode()


def _array(name, values, components=1, code="f", kind="Float32"):
    label = f' Name="{name}"' if name else ""
    return (f'<DataArray type="{kind}"{label} NumberOfComponents='
            f'"{components}" format="binary">\n{_binary(values, code)}\n'
            "</DataArray>\n")


def _fields(points):
    """Scalars by name, and vectors NAME from NAME_0..NAME_2."""
    names = sorted({k for p in points for k in p if k not in ("x", "y")})
    vectors = sorted({n[:-2] for n in names if n.endswith("_0")
                      and n[:-2] + "_1" in names})
    scalars = [n for n in names
               if not any(n in (v + "_0", v + "_1", v + "_2")
                          for v in vectors)]
    return scalars, vectors


def write_piece(name, points):
    n = len(points)
    xyz = [c for p in points for c in (p["x"], p["y"], 0.0)]
    scalars, vectors = _fields(points)
    text = ('<?xml version="1.0" ?>\n<VTKFile type="UnstructuredGrid" '
            'version="0.1" compressor="vtkZLibDataCompressor" '
            'byte_order="LittleEndian">\n<UnstructuredGrid>\n'
            f'<Piece NumberOfPoints="{n}" NumberOfCells="{n}">\n<Points>\n')
    text += _array(None, xyz, 3) + "</Points>\n<Cells>\n"
    text += _array("connectivity", list(range(n)), 1, "i", "Int32")
    text += _array("offsets", list(range(1, n + 1)), 1, "i", "Int32")
    text += _array("types", [1] * n, 1, "B", "UInt8")
    text += "</Cells>\n<PointData>\n"
    for v in vectors:
        text += _array(v, [p.get(f"{v}_{c}", 0.0) for p in points
                           for c in range(3)], 3)
    for s in scalars:
        text += _array(s, [p[s] for p in points])
    text += "</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n"
    with open(name, "w") as f:
        f.write(text)


def write_run(directory, outputs):
    """outputs: [(time, [piece, ...]), ...], a piece a list of points."""
    os.makedirs(directory, exist_ok=True)
    pvd = ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" '
           'ByteOrder="LittleEndian">\n  <Collection>\n')
    for index, (time, pieces) in enumerate(outputs):
        stem = "particles_%05d" % index
        sources = ""
        for rank, piece in enumerate(pieces):
            write_piece(os.path.join(directory, f"{stem}.{rank}.vtu"), piece)
            sources += f'    <Piece Source="{stem}.{rank}.vtu"/>\n'
        with open(os.path.join(directory, stem + ".pvtu"), "w") as f:
            f.write('<?xml version="1.0"?>\n<VTKFile type="PUnstructuredGrid"'
                    ' version="0.1" byte_order="LittleEndian">\n'
                    '  <PUnstructuredGrid GhostLevel="0">\n' + sources +
                    "  </PUnstructuredGrid>\n</VTKFile>\n")
        pvd += (f'    <DataSet timestep="{time!r}" group="" part="0" '
                f'file="{stem}.pvtu"/>\n')
    with open(os.path.join(directory, "particles.pvd"), "w") as f:
        f.write(pvd + "  </Collection>\n</VTKFile>\n")
