"""Cases as `sphd.Case` messages: parsed from text format, with the point files and reference
data a case names read in, as sphctl does before submitting (case/load.cc): the server cannot
read files on the client's machine."""
import os

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
    for group in ("fluids", "walls", "bodies", "elastic_bodies"):
        for i, region in enumerate(getattr(case, group)):
            _inline_shape(region.shape, base, f"{group}[{i}].shape")
    _inline_reference_data(case, base)
    return case


def _inline_shape(shape, base, field):
    kind = shape.WhichOneof("kind")
    if kind == "points" and shape.points.file:
        path = os.path.join(base, shape.points.file)
        for x, y, z in _read_points(path, field + ".points.file"):
            p = shape.points.points.add()
            p.x, p.y, p.z = x, y, z
        shape.points.ClearField("file")
    elif kind in ("union", "intersection"):
        for i, s in enumerate(getattr(shape, kind).shapes):
            _inline_shape(s, base, f"{field}.{kind}.shapes[{i}]")
    elif kind == "difference":
        _inline_shape(shape.difference.base, base, field + ".difference.base")
        for i, s in enumerate(shape.difference.subtract):
            _inline_shape(s, base, f"{field}.difference.subtract[{i}]")
    elif kind == "shell":
        _inline_shape(shape.shell.inner, base, field + ".shell.inner")


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
