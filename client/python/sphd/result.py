"""sphd.Result: a run's result.h5 (solver/io/result_file.h) as numpy arrays.

    /meta                       attributes: the case text, code version, status, units, ...
    /snapshots/NNNNNN/<field>   particle fields at one output time (attributes time, step, count)
    /series/<group>/<name>      time series, first dimension the samples; each group has its own
                                `time`, or shares /series/diagnostics/time
"""
import os

import h5py
import numpy as np

from sphd.case_file import parse_case


class Snapshot:
    """The particle fields at one output time: snapshot["position"] is an (n, 3) array;
    `time`, `step` and `index` say which output it is."""

    def __init__(self, index, time, step, fields):
        self.index, self.time, self.step = index, time, step
        self._fields = fields

    def __getitem__(self, name):
        try:
            return self._fields[name]
        except KeyError:
            raise KeyError(f"no field '{name}' in snapshot {self.index} (t = {self.time}); "
                           f"fields: {', '.join(self._fields)}") from None

    def __contains__(self, name):
        return name in self._fields

    def keys(self):
        return self._fields.keys()

    def __len__(self):
        """The number of particles."""
        return len(self._fields["id"]) if "id" in self._fields else 0

    def __repr__(self):
        return f"Snapshot({self.index}, t={self.time:g}, {len(self)} particles)"


class Result:
    """A result file. `path` is result.h5 or the folder that holds it. The file is read when
    asked and closed in between, so a running job's growing file can be read again."""

    def __init__(self, path):
        path = os.fspath(path)
        if os.path.isdir(path):
            path = os.path.join(path, "result.h5")
        if not os.path.isfile(path):
            raise FileNotFoundError(f"no result file '{path}'")
        self.path = path
        with self._open() as f:
            self._snapshot_names = sorted(f["snapshots"].keys()) if "snapshots" in f else []
            self.times = np.array([f["snapshots"][n].attrs["time"] for n in self._snapshot_names],
                                  dtype=float)
            self.steps = np.array([f["snapshots"][n].attrs["step"] for n in self._snapshot_names],
                                  dtype=np.int64)
            self.meta = {k: _attr(v) for k, v in f["meta"].attrs.items()} if "meta" in f else {}

    def _open(self):
        return h5py.File(self.path, "r")

    def __repr__(self):
        return (f"Result('{self.path}': {len(self.times)} snapshots, series "
                f"{', '.join(self.series_groups())})")

    # -- the case -------------------------------------------------------------------------------

    @property
    def case(self):
        """The case that ran (sphd.Case), from /meta case_text."""
        return parse_case(self.meta["case_text"])

    # -- snapshots ------------------------------------------------------------------------------

    def __len__(self):
        return len(self.times)

    def snapshot(self, index=None, time=None):
        """The snapshot with this index (negative counts from the end), or the one nearest to
        `time`. All its fields are read."""
        if (index is None) == (time is None):
            raise ValueError("snapshot needs index= or time=")
        if not len(self.times):
            raise IndexError(f"{self.path} holds no snapshots")
        if time is not None:
            index = int(np.argmin(np.abs(self.times - time)))
        index = range(len(self.times))[index]  # IndexError with the usual message
        name = self._snapshot_names[index]
        with self._open() as f:
            g = f["snapshots"][name]
            fields = {k: g[k][()] for k in g.keys()}
        return Snapshot(index, float(self.times[index]), int(self.steps[index]), fields)

    def snapshots(self):
        """Every snapshot in time order (an iterator: one is in memory at a time)."""
        for k in range(len(self.times)):
            yield self.snapshot(k)

    def field(self, name, time=None, index=None):
        """One particle field at one time (the nearest snapshot), e.g. field("pressure", 0.5);
        default the last snapshot."""
        if time is None and index is None:
            index = -1
        return self.snapshot(index=index, time=time)[name]

    def fields(self):
        """The names of the fields in the first snapshot."""
        with self._open() as f:
            return sorted(f["snapshots"][self._snapshot_names[0]].keys()) if self._snapshot_names \
                else []

    # -- series ---------------------------------------------------------------------------------

    def series_groups(self):
        """The series groups: 'diagnostics', 'probes/<name>', 'bodies', 'phase', 'elastic/<name>'
        and others, each a folder of datasets."""
        groups = []
        with self._open() as f:
            if "series" not in f:
                return groups

            def visit(name, obj):
                if isinstance(obj, h5py.Group) and any(
                        isinstance(v, h5py.Dataset) for v in obj.values()):
                    groups.append(name)
            f["series"].visititems(visit)
        return sorted(groups)

    def series(self, group="diagnostics"):
        """The group's series as a dict of arrays (first dimension the samples), with its
        `time` (its own, or the diagnostics' clock it shares)."""
        with self._open() as f:
            if "series/" + group not in f:
                raise KeyError(f"no series group '{group}' in {self.path}; groups: "
                               f"{', '.join(self.series_groups())}")
            g = f["series/" + group]
            out = {k: v[()] for k, v in g.items() if isinstance(v, h5py.Dataset)}
            if "time" not in out:
                out["time"] = f["series/diagnostics/time"][()]
        return out

    def frame(self, group="diagnostics"):
        """The group's series as a pandas DataFrame indexed by time; a vector series becomes
        columns NAME_x, NAME_y (NAME_z), other shapes NAME_0, NAME_1, ... (pandas needed)."""
        import pandas as pd
        data = self.series(group)
        time = data.pop("time")
        columns = {}
        for name, a in data.items():
            a = a.reshape(len(a), -1)
            if a.shape[1] == 1:
                columns[name] = a[:, 0]
            else:
                suffixes = "xyz" if a.shape[1] <= 3 else range(a.shape[1])
                for k, s in zip(range(a.shape[1]), suffixes):
                    columns[f"{name}_{s}"] = a[:, k]
        return pd.DataFrame(columns, index=pd.Index(time, name="time"))

    def bodies(self):
        """Per-body series of the rigid bodies: {name: {series: array}}. The series have one
        column per body slot, slot k named after the case's k-th body; melting can empty a slot
        and hand it to a body made later, which the slot's `serial` series tells (README)."""
        data = self.series("bodies")
        time = data.pop("time")
        names = [b.name or f"body_{k}" for k, b in enumerate(self.case.bodies)]
        out = {}
        for k, name in enumerate(names):
            out[name] = {s: a[:, k] for s, a in data.items() if a.ndim >= 2 and a.shape[1] > k}
            out[name]["time"] = time
        return out

    def probe(self, name):
        """The series of the probe set `name`."""
        return self.series("probes/" + name)


def _attr(v):
    if isinstance(v, bytes):
        return v.decode("utf-8", "replace")
    if isinstance(v, np.ndarray) and v.shape == ():
        v = v[()]
    if isinstance(v, np.generic):
        return v.item()
    return v
