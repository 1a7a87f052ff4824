"""Cases as `sphd.Case` messages: parsed from text format, with the point, polygon, STL mesh,
distance-grid and reference data files a case names read in, as sphctl does before submitting
(case/load.cc): the server cannot read files on the client's machine."""
import math
import os
import struct

from google.protobuf import text_format

from sphd.errors import InvalidCase
from sphd.proto import case_pb2


def parse_case(text):
    """A Case from its text format; InvalidCase names the line and column of a mistake."""
    case = case_pb2.Case()
    try:
        text_format.Parse(text, case)
    except text_format.ParseError as e:
        # Worded as case/load.cc words it: "line L, column C: what".
        what = str(e).split(" : ", 1)[-1]
        where = f"line {e.GetLine()}, column {e.GetColumn()}: " if e.GetLine() else ""
        raise InvalidCase(f"malformed case text: {where}{what}") from None
    return case


def load_case(path):
    """The case in the file `path` with its point and reference data files inlined (relative
    names are relative to the case file's folder)."""
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        raise InvalidCase(f"cannot read '{path}': {e.strerror}") from None
    try:
        case = parse_case(text)
    except InvalidCase as e:
        raise InvalidCase(f"{path}: {e}") from None
    base = os.path.dirname(os.path.abspath(path))
    # What the case holds inline counts against the limits too (case/load.cc does the same).
    budget = {"triangles": 0, "nodes": 0, "dimension": case.dimension}
    for group in ("fluids", "walls", "bodies", "elastic_bodies"):
        for region in getattr(case, group):
            _count_inline(region.shape, budget)
    for group in ("fluids", "walls", "bodies", "elastic_bodies"):
        for i, region in enumerate(getattr(case, group)):
            _inline_shape(region.shape, base, f"{group}[{i}].shape", budget)
    _inline_reference_data(case, base)
    return case


# The limits of case/case_limits.h that reading files can break.
MAX_MESH_TRIANGLES = 500000
MAX_DISTANCE_GRID_NODES = 1000000


def _inline_shape(shape, base, field, budget):
    kind = shape.WhichOneof("kind")
    if kind == "points" and shape.points.file:
        path = os.path.join(base, shape.points.file)
        for x, y, z in _read_points(path, field + ".points.file"):
            p = shape.points.points.add()
            p.x, p.y, p.z = x, y, z
        shape.points.ClearField("file")
    elif kind == "polygon" and shape.polygon.file:
        path = os.path.join(base, shape.polygon.file)
        for x, y, z in _read_points(path, field + ".polygon.file"):
            v = shape.polygon.vertices.add()
            v.x, v.y, v.z = x, y, z
        shape.polygon.ClearField("file")
    elif kind == "mesh" and shape.mesh.file:
        path = os.path.join(base, shape.mesh.file)
        left = max(0, MAX_MESH_TRIANGLES - budget["triangles"])
        vertices, triangles = _read_stl(path, field + ".mesh.file", left)
        shape.mesh.vertices.extend(vertices)
        shape.mesh.triangles.extend(triangles)
        budget["triangles"] += len(triangles) // 3
        shape.mesh.ClearField("file")
    elif kind == "distance_grid" and shape.distance_grid.file:
        path = os.path.join(base, shape.distance_grid.file)
        budget["nodes"] -= len(shape.distance_grid.values)  # the file's values replace these
        left = max(0, MAX_DISTANCE_GRID_NODES - budget["nodes"])
        _read_distance_grid(path, field + ".distance_grid.file", budget["dimension"], left,
                            shape.distance_grid)
        budget["nodes"] += len(shape.distance_grid.values)
        shape.distance_grid.ClearField("file")
    elif kind in ("union", "intersection"):
        for i, s in enumerate(getattr(shape, kind).shapes):
            _inline_shape(s, base, f"{field}.{kind}.shapes[{i}]", budget)
    elif kind == "difference":
        _inline_shape(shape.difference.base, base, field + ".difference.base", budget)
        for i, s in enumerate(shape.difference.subtract):
            _inline_shape(s, base, f"{field}.difference.subtract[{i}]", budget)
    elif kind == "shell":
        _inline_shape(shape.shell.inner, base, field + ".shell.inner", budget)


def _count_inline(shape, budget):
    kind = shape.WhichOneof("kind")
    if kind == "mesh":
        budget["triangles"] += len(shape.mesh.triangles) // 3
    elif kind == "distance_grid":
        budget["nodes"] += len(shape.distance_grid.values)
    elif kind in ("union", "intersection"):
        for s in getattr(shape, kind).shapes:
            _count_inline(s, budget)
    elif kind == "difference":
        for s in [shape.difference.base] + list(shape.difference.subtract):
            _count_inline(s, budget)
    elif kind == "shell":
        _count_inline(shape.shell.inner, budget)


def _read_stl(path, field, max_triangles):
    """Vertices (x, y, z flat) and triangles (three indices each) of a binary or ASCII STL
    file, vertices with equal coordinates welded into one, in the order of case/mesh/
    triangle_mesh.cc read_stl: a binary file is exactly 84 + 50 n bytes long."""
    def fail(what):
        raise InvalidCase(f"{field}: STL file '{path}': {what}") from None
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise InvalidCase(f"{field}: STL file '{path}': cannot be read: {e.strerror}") from None
    vertices, triangles, ids = [], [], {}

    def index(x, y, z):
        key = (x, y, z)
        if key not in ids:
            ids[key] = len(vertices) // 3
            vertices.extend(key)
        return ids[key]

    count = struct.unpack_from("<I", data, 80)[0] if len(data) >= 84 else -1
    if len(data) >= 84 and len(data) == 84 + 50 * count:
        if count > max_triangles:
            fail(f"has {count} triangles; the limit is {max_triangles} (what the case's limit "
                 "of mesh triangles leaves for it)")
        if count == 0:
            fail("holds no triangles")
        for t in range(count):
            xyz = struct.unpack_from("<9f", data, 84 + 50 * t + 12)
            if not all(math.isfinite(c) for c in xyz):
                fail(f"triangle {t} has a coordinate that is not a number")
            for k in range(3):
                triangles.append(index(*xyz[3 * k:3 * k + 3]))
        return vertices, triangles
    if not data.startswith(b"solid"):
        fail(f"is neither binary STL ({len(data)} bytes, not 84 + 50 x {count}) nor ASCII STL "
             "(no leading 'solid')")
    words = data.decode("ascii", errors="replace").split()
    corners = 0
    i = 0
    while i < len(words):
        if words[i] == "vertex":
            try:
                x, y, z = (float(w) for w in words[i + 1:i + 4])
            except ValueError:
                x = y = z = math.nan
            if i + 4 > len(words) or not all(math.isfinite(c) for c in (x, y, z)):
                fail(f"a 'vertex' is not followed by three numbers (triangle "
                     f"{len(triangles) // 3})")
            if len(triangles) // 3 >= max_triangles and corners == 0:
                fail(f"has more than {max_triangles} triangles, all the case's limit of mesh "
                     "triangles leaves for it")
            triangles.append(index(x, y, z))
            corners = (corners + 1) % 3
            i += 4
            continue
        if words[i] == "endloop" and corners != 0:
            fail(f"a facet has {corners} vertices, not 3")
        i += 1
    if corners != 0:
        fail("ends inside a facet")
    if not triangles:
        fail("holds no triangles (neither binary nor ASCII STL)")
    return vertices, triangles


def _read_distance_grid(path, field, dimension, max_nodes, grid):
    """Dataset `grid.dataset` (default "sdf") of an HDF5 file into grid.counts (x, y, z order)
    and grid.values (x fastest), as case/distance_grid/read_distance_grid.cc."""
    import h5py  # a dependency of the package (sphd.Result reads results with it)
    import numpy as np
    name = grid.dataset or "sdf"
    where = f"{field}: '{path}'"
    if not os.path.isfile(path):
        raise InvalidCase(f"{field}: cannot read '{path}': no such file")
    try:
        f = h5py.File(path, "r")
    except OSError:
        raise InvalidCase(f"{where} is not an HDF5 file") from None
    with f:
        if name not in f:
            raise InvalidCase(f"{where} has no dataset '{name}' (DistanceGrid.dataset names it; "
                              'the default is "sdf")')
        d = f[name]
        if not isinstance(d, h5py.Dataset):
            raise InvalidCase(f"{where}: '{name}' is not a dataset")
        if d.dtype.kind not in "fiu":
            raise InvalidCase(f"{where}: dataset '{name}' is not numeric (floating-point or "
                              "integer values needed)")
        if d.ndim != dimension:
            raise InvalidCase(f"{where}: dataset '{name}' has {d.ndim} axes; a {dimension}D case "
                              f"needs {dimension} ([nz][ny][nx] in 3D, [ny][nx] in 2D)")
        if min(d.shape) < 2:
            raise InvalidCase(f"{where}: dataset '{name}' has {min(d.shape)} nodes along an "
                              "axis; at least 2 are needed")
        if math.prod(d.shape) > max_nodes:
            raise InvalidCase(f"{where}: dataset '{name}' has more nodes than the case may hold; "
                              f"the limit is {max_nodes} grid nodes per case")
        values = np.asarray(d[()], dtype=np.float32)
    grid.ClearField("counts")
    grid.counts.extend(reversed(values.shape))
    grid.ClearField("values")
    grid.values.extend(values.ravel().tolist())


def _read_points(path, field):
    """'x y [z]' lines, '#' starts a comment (case/load.cc read_point_file)."""
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.readlines()
    except OSError as e:
        raise InvalidCase(f"{field}: cannot read point file '{path}': {e.strerror}") from None
    points = []
    for number, line in enumerate(lines, 1):
        words = line.split("#", 1)[0].split()
        if not words:
            continue
        try:
            xyz = [float(w) for w in words]
        except ValueError:
            xyz = []
        if len(xyz) not in (2, 3):
            raise InvalidCase(f"{field}: {path}:{number}: expected 'x y' or 'x y z'")
        points.append((xyz + [0.0])[:3])
    return points


def _inline_reference_data(case, base):
    """reference.series_data.file: a CSV with '#' comments, a header line, then numbers; column
    0 is the time (case/reference_data.cc)."""
    if not case.HasField("reference") or case.reference.WhichOneof("kind") != "series_data":
        return
    data = case.reference.series_data
    if not data.file:
        return
    field = "reference.series_data.file"
    path = os.path.join(base, data.file)
    column = data.column or 1
    try:
        with open(path, encoding="utf-8") as f:
            lines = [l.strip() for l in f if l.strip() and not l.startswith("#")]
    except OSError as e:
        raise InvalidCase(f"{field}: cannot read {path}: {e.strerror}") from None
    del data.times[:]
    del data.values[:]
    for number, line in enumerate(lines[1:], 1):
        try:
            row = [float(c) for c in line.split(",")]
        except ValueError:
            raise InvalidCase(f"{field}: {path} data row {number} is not numbers: '{line}'") from None
        if len(row) <= column:
            raise InvalidCase(f"{field}: {path} data row {number} has no column {column}")
        data.times.append(row[0])
        data.values.append(row[column])
    data.ClearField("file")
