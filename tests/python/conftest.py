"""A real sph-server and a real one-rank worker pool on loopback for the Python client's tests,
started the way tests/service/harness does: ephemeral port, temporary database and results.
ctest passes the binaries in SPHD_SERVER_BIN, SPHD_WORKER_BIN and SPHD_MPIRUN ('|'-joined) and
the staged package on PYTHONPATH (tests/python/CMakeLists.txt)."""
import os
import signal
import subprocess
import time

import pytest

import sphd

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASES = os.path.join(ROOT, "tests", "service", "cases")


def _env(name):
    value = os.environ.get(name)
    if not value:
        pytest.skip(f"{name} is not set (run through ctest -L python)")
    return value


class Server:
    """sph-server in `dir`; restart() brings it back on the same address and database."""

    def __init__(self, dir, token=None, lease=3):
        self.dir = dir
        self.address = "127.0.0.1:0"
        self.token_file = None
        if token:
            self.token_file = os.path.join(dir, "token")
            with open(self.token_file, "w") as f:
                f.write(token + "\n")
        self.lease = lease
        self.proc = None
        self.starts = 0
        self.start()

    def start(self):
        address_file = os.path.join(self.dir, "server.address")
        if os.path.exists(address_file):
            os.remove(address_file)
        argv = [_env("SPHD_SERVER_BIN"), "--address", self.address, "--address-file",
                address_file, "--db", os.path.join(self.dir, "sphd.db"), "--results",
                os.path.join(self.dir, "results"), "--lease", str(self.lease),
                "--shutdown-grace", "3"]
        if self.token_file:
            argv += ["--token-file", self.token_file]
        self.starts += 1
        self.log = os.path.join(self.dir, f"server{self.starts}.log")
        self.proc = subprocess.Popen(argv, stdout=open(self.log, "w"), stderr=subprocess.STDOUT,
                                     start_new_session=True)
        deadline = time.monotonic() + 20
        while not os.path.exists(address_file):
            if self.proc.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError("sph-server did not start:\n" + open(self.log).read())
            time.sleep(0.05)
        time.sleep(0.05)  # the file is written whole, but give the writer its close
        self.address = open(address_file).read().strip()

    def stop(self, sig=signal.SIGTERM):
        if self.proc and self.proc.poll() is None:
            self.proc.send_signal(sig)
            try:
                self.proc.wait(15)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()

    def client(self, **kw):
        return sphd.Client(self.address, token_file=self.token_file, **kw)


class Pool:
    """`mpirun -np RANKS sph-worker --server ADDR` in its own session."""

    def __init__(self, server, ranks=1, log="pool.log"):
        argv = _env("SPHD_MPIRUN").split("|") + ["-np", str(ranks), _env("SPHD_WORKER_BIN"),
                                                  "--server", server.address]
        if server.token_file:
            argv += ["--token-file", server.token_file]
        self.log = os.path.join(server.dir, log)
        self.proc = subprocess.Popen(argv, stdout=open(self.log, "w"), stderr=subprocess.STDOUT,
                                     start_new_session=True)

    def stop(self):
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGTERM)
            try:
                self.proc.wait(20)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()


@pytest.fixture(scope="module")
def service(tmp_path_factory):
    """A server with a one-rank pool, shared by a test module."""
    dir = str(tmp_path_factory.mktemp("service"))
    server = Server(dir)
    pool = Pool(server)
    yield server
    pool.stop()
    server.stop()


def case_path(name):
    return os.path.join(CASES, name)


def with_end_time(path, end_time):
    """The case in `path` with time.end_time replaced."""
    case = sphd.load_case(path)
    case.time.end_time = end_time
    return case
