"""sphd.Client against a real server and pool: the calls of sphctl, their errors, watching
across a server restart, verified fetches (tests/python/conftest.py starts the service)."""
import hashlib
import os
import time

import pytest

import sphd
from conftest import ROOT, Pool, Server, case_path, with_end_time


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def test_submit_watch_fetch_and_read(service, tmp_path):
    client = service.client()
    job = client.submit(case_path("tiny_dam_break_2d.textproto"), request_id="py-first")
    assert job.id.startswith("job-") and job.name == "tiny_dam_break_2d"
    again = client.submit(case_path("tiny_dam_break_2d.textproto"), request_id="py-first")
    assert again.id == job.id, "the same request id must return the same job"

    events = list(client.watch(job.id))
    sequences = [e.sequence for e in events]
    print(f"{len(events)} events, sequences {sequences[0]}..{sequences[-1]}")
    assert sequences == list(range(1, len(events) + 1)), "a gap in the events"
    kinds = [e.WhichOneof("kind") for e in events]
    assert "progress" in kinds and "result_ready" in kinds
    assert events[-1].state_change.state == sphd.JobState.Value("JOB_STATE_SUCCEEDED")
    # Resuming after a sequence gives the rest, as sphctl watch --from.
    assert [e.sequence for e in client.watch(job.id, after_sequence=3)] == sequences[3:]

    done = client.status(job.id, include_case=True)
    assert sphd.state_name(done.state) == "SUCCEEDED"
    assert "tiny_dam_break_2d" in done.case_text and len(done.attempts) == 1
    listed = client.list(states=["SUCCEEDED"], limit=0)
    assert job.id in [j.id for j in listed]
    assert client.list(states=["QUEUED"]) == []

    paths = client.fetch(job.id, tmp_path / "fetched")
    names = sorted(os.path.basename(p) for p in paths)
    assert names == sorted(f.name for f in done.result.files)
    assert "result.h5" in names and "result.xmf" in names
    for f in done.result.files:
        assert sha256(tmp_path / "fetched" / f.name) == f.sha256
        # The same bytes as the file the pool wrote.
        assert sha256(os.path.join(done.result.output_dir, f.name)) == f.sha256
    assert not any(n.endswith(".part") for n in os.listdir(tmp_path / "fetched"))
    only = client.fetch(job.id, tmp_path / "only", file="result.xmf")
    assert [os.path.basename(p) for p in only] == ["result.xmf"]

    result = sphd.Result(tmp_path / "fetched")
    print(result)
    # end_time 0.1, output interval 0.02: six snapshots at those times.
    assert result.times == pytest.approx([0, 0.02, 0.04, 0.06, 0.08, 0.1], abs=1e-12)
    last = result.snapshot(-1)
    assert len(last) == 606 and last["position"].shape == (606, 3)
    assert result.snapshot(time=0.061).index == 3
    assert result.field("pressure", time=0.1).shape == (606,)
    assert result.case.name == "tiny_dam_break_2d"
    assert result.meta["status"] and "code_version" in result.meta
    d = result.series("diagnostics")
    assert (d["time"][1:] > d["time"][:-1]).all() and d["time"][-1] == pytest.approx(0.1)
    assert d["fluid_max"].shape == (len(d["time"]), 2)
    # Mass is conserved exactly: no particle is created or deleted in this case.
    assert d["mass"] == pytest.approx(d["mass"][0], rel=1e-12)


def test_frame_needs_pandas(service, tmp_path):
    pd = pytest.importorskip("pandas")
    client = service.client()
    job = client.submit(with_end_time(case_path("tiny_dam_break_2d.textproto"), 0.02))
    client.wait(job.id)
    client.fetch(job.id, tmp_path)
    frame = sphd.Result(tmp_path).frame()
    assert isinstance(frame, pd.DataFrame) and frame.index.name == "time"
    assert {"fluid_max_x", "fluid_max_y", "kinetic_energy"} <= set(frame.columns)


def test_errors_are_sphctls(service, tmp_path):
    client = service.client()
    with pytest.raises(sphd.NotFound) as e:
        client.status("job-999")
    assert e.value.exit_code == 4
    bad = sphd.load_case(case_path("tiny_dam_break_2d.textproto"))
    bad.fluids[0].material = "oil"
    with pytest.raises(sphd.InvalidCase) as e:
        client.submit(bad)
    print("invalid case:", e.value)
    assert "fluids[0].material" in str(e.value) and e.value.exit_code == 3
    with pytest.raises(sphd.InvalidCase, match="line 1"):
        sphd.parse_case("dimension: two")
    with pytest.raises(sphd.InvalidCase, match="cannot read"):
        client.submit(str(tmp_path / "missing.textproto"))
    with pytest.raises(sphd.Conflict):  # the same request id with another case
        client.submit(with_end_time(case_path("tiny_dam_break_2d.textproto"), 0.04),
                      request_id="py-first")
    with pytest.raises(sphd.Unavailable) as e:
        sphd.Client("127.0.0.1:1", timeout=1).status("job-1")
    assert "127.0.0.1:1" in str(e.value) and e.value.exit_code == 5


def test_environment_variables(service, monkeypatch, tmp_path):
    monkeypatch.setenv("SPHCTL_SERVER", service.address)
    assert sphd.Client().address == service.address
    sphd.Client().list()
    monkeypatch.delenv("SPHCTL_SERVER")
    assert sphd.Client().address == "127.0.0.1:7070"
    monkeypatch.setenv("SPHCTL_TOKEN_FILE", str(tmp_path / "none"))
    with pytest.raises(sphd.SphdError, match="cannot read token file"):
        sphd.Client(service.address)


def test_cancel(service):
    client = service.client()
    job = client.submit(with_end_time(case_path("channel_2d.textproto"), 100))
    cancelled = client.cancel(job.id, reason="from python")
    assert cancelled.cancel_requested or cancelled.state == sphd.JobState.Value(
        "JOB_STATE_CANCELLED")
    events = []
    with pytest.raises(sphd.JobCancelled) as e:
        client.wait(job.id, on_event=events.append)
    print("cancelled:", e.value)
    assert e.value.exit_code == 11 and e.value.job.reason
    assert [ev.cancel_requested.reason for ev in events if ev.HasField("cancel_requested")] == [
        "cancelled: from python"]
    assert sphd.state_name(client.status(job.id).state) == "CANCELLED"


def test_logs(service):
    client = service.client()
    job = client.submit(with_end_time(case_path("tiny_dam_break_2d.textproto"), 0.6))
    followed = list(client.logs(job.id, follow=True))  # to the guard that stops it
    texts = [l.text for l in followed]
    print("\n".join(texts))
    assert texts[0].startswith("tiny_dam_break_2d, output ")
    assert any(t.startswith("progress step ") for t in texts)
    assert "solid fraction" in texts[-1] and "(guards.max_solid_fraction)" in texts[-1]
    assert [l.sequence for l in followed] == list(range(1, len(followed) + 1))
    assert [l.text for l in client.logs(job.id, after_sequence=2)] == texts[2:]
    assert list(client.logs(job.id, attempt=2)) == []
    with pytest.raises(sphd.NotFound):
        list(client.logs("job-999"))


def test_token(tmp_path):
    server = Server(str(tmp_path), token="s3cret")
    try:
        with pytest.raises(sphd.AuthError) as e:
            sphd.Client(server.address).list()
        assert e.value.exit_code == 6 and "SPHCTL_TOKEN_FILE" in str(e.value)
        assert server.client().list() == []
    finally:
        server.stop()


def test_watch_resumes_across_a_server_restart(tmp_path):
    server = Server(str(tmp_path), lease=5)
    pool = Pool(server)
    try:
        client = server.client()
        job = client.submit(with_end_time(case_path("channel_2d.textproto"), 2))
        events = []
        restarted = False
        for event in client.watch(job.id):
            events.append(event)
            if event.HasField("progress") and not restarted:
                server.stop()  # SIGTERM: the stream ends UNAVAILABLE
                time.sleep(1)
                server.start()
                restarted = True
        assert restarted
        sequences = [e.sequence for e in events]
        print(f"{len(events)} events across the restart")
        assert sequences == list(range(1, len(events) + 1)), "an event lost or repeated"
        assert events[-1].state_change.state == sphd.JobState.Value("JOB_STATE_SUCCEEDED")
    finally:
        pool.stop()
        server.stop()


def test_fetch_refuses_a_file_that_changed(service, tmp_path):
    client = service.client()
    job = client.submit(with_end_time(case_path("tiny_dam_break_2d.textproto"), 0.02))
    done = client.wait(job.id)
    xmf = os.path.join(done.result.output_dir, "result.xmf")
    with open(xmf, "r+b") as f:  # same size, one byte different
        first = f.read(1)
        f.seek(0)
        f.write(b"X" if first != b"X" else b"Y")
    with pytest.raises(sphd.VerifyFailed) as e:
        client.fetch(job.id, tmp_path, file="result.xmf")
    print("changed file:", e.value)
    assert e.value.exit_code == 7
    assert not os.path.exists(tmp_path / "result.xmf")
    assert not os.path.exists(tmp_path / "result.xmf.part")


def test_geometry_files_are_inlined_as_sphctl_does(service, tmp_path):
    """An STL mesh (3D) and a signed-distance grid in HDF5 (2D), each read by load_case and run
    by the server, which refuses a case with a file left in it."""
    client = service.client()
    shipped = os.path.join(ROOT, "cases")
    sdf = sphd.load_case(os.path.join(shipped, "dambreak_sdf_obstacle_2d.textproto"))
    grid = sdf.walls[1].shape.distance_grid
    # [ny][nx] in the file, counts in x, y order; the boulder's centre node is -0.3.
    assert not grid.file and list(grid.counts) == [131, 91] and len(grid.values) == 131 * 91
    assert grid.values[45 * 131 + 50] == pytest.approx(-0.3, abs=1e-6)
    funnel = sphd.load_case(os.path.join(shipped, "funnel_spheres_3d.textproto"))
    block = funnel.walls[1].shape.mesh
    # Welded as case/mesh/triangle_mesh.cc welds: a closed surface, V - E + F = 2.
    v, f = len(block.vertices) // 3, len(block.triangles) // 3
    print(f"funnel block: {v} vertices, {f} triangles; boulder grid {list(grid.counts)}")
    assert not block.file and v - 3 * f // 2 + f == 2
    for case in (sdf, funnel):
        case.time.max_steps = 3
        job = client.submit(case)
        assert sphd.state_name(client.wait(job.id).state) == "SUCCEEDED", case.name
    # What sphctl says of a missing dataset, a missing file and an STL cut short.
    bad = tmp_path / "bad.textproto"
    text = open(os.path.join(shipped, "dambreak_sdf_obstacle_2d.textproto")).read()
    # Parsed without load_case, the grid's file is still named: the server refuses it.
    with pytest.raises(sphd.InvalidCase, match="must be inlined"):
        client.submit(sphd.parse_case(text))
    os.makedirs(tmp_path / "geometry")
    with open(os.path.join(shipped, "geometry", "boulder_sdf_2d.h5"), "rb") as src:
        (tmp_path / "geometry" / "boulder_sdf_2d.h5").write_bytes(src.read())
    bad.write_text(text.replace("spacing: 0.01", 'spacing: 0.01 dataset: "phi"'))
    with pytest.raises(sphd.InvalidCase, match=r"walls\[1\].shape.distance_grid.file: .* has no "
                                                 "dataset 'phi'"):
        sphd.load_case(str(bad))
    bad.write_text(text.replace("boulder_sdf_2d.h5", "missing.h5"))
    with pytest.raises(sphd.InvalidCase, match="no such file"):
        sphd.load_case(str(bad))
    with open(os.path.join(shipped, "geometry", "funnel_block.stl"), "rb") as src:
        (tmp_path / "geometry" / "cut.stl").write_bytes(src.read()[:-30])
    bad.write_text(open(os.path.join(shipped, "funnel_spheres_3d.textproto")).read().replace(
        "funnel_block.stl", "cut.stl"))
    # The fluid, a tank minus the funnel, names the file first.
    with pytest.raises(sphd.InvalidCase, match=r"fluids\[0\].shape.difference.subtract\[0\]"
                                                 r".mesh.file: STL file .*cut.stl': is neither"):
        sphd.load_case(str(bad))
