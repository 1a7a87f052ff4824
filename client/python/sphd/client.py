"""sphd.Client: the JobService of sph-server from Python, behaving as sphctl does: the same
server address and token file (arguments, else $SPHCTL_SERVER and $SPHCTL_TOKEN_FILE, else
127.0.0.1:7070 and no token), the same retries (submit while the server is unreachable, watch
across a restart, fetch from the last byte received) and the same errors (sphd.errors)."""
import hashlib
import os
import secrets
import time

import grpc

from sphd.case_file import load_case
from sphd.errors import (Conflict, JobCancelled, JobFailed, NotFound, SphdError, Unavailable,
                         VerifyFailed, from_rpc_error)
from sphd.proto import case_pb2, service_pb2, service_pb2_grpc, study_pb2

DEFAULT_ADDRESS = "127.0.0.1:7070"
# common/message_limits.h
MAX_MESSAGE_BYTES = 64 << 20
MAX_CASE_TEXT_BYTES = 48 << 20
# sphctl's retry windows (client/commands/submit.cc, watch.cc).
SUBMIT_RETRY_SECONDS = 30
WATCH_RECONNECT_SECONDS = 120
FETCH_RETRIES = 20

_TERMINAL = (service_pb2.JOB_STATE_SUCCEEDED, service_pb2.JOB_STATE_FAILED,
             service_pb2.JOB_STATE_CANCELLED)


def state_name(state):
    """'QUEUED', 'RUNNING', ... as sphctl prints them."""
    return service_pb2.JobState.Name(state).replace("JOB_STATE_", "")


def is_terminal(state):
    return state in _TERMINAL


class Client:
    """A connection to sph-server's JobService.

    address: HOST:PORT, default $SPHCTL_SERVER, else 127.0.0.1:7070.
    token_file: a file whose first line is the server's token, default $SPHCTL_TOKEN_FILE.
    timeout: seconds for each unary call (streams have none, as in sphctl).
    """

    def __init__(self, address=None, token_file=None, timeout=30.0):
        self.address = address or os.environ.get("SPHCTL_SERVER") or DEFAULT_ADDRESS
        token_file = token_file or os.environ.get("SPHCTL_TOKEN_FILE") or None
        self._metadata = ()
        if token_file:
            self._metadata = (("authorization", "Bearer " + _read_token(token_file)),)
        self.timeout = timeout
        # The reconnect backoff of common/channel.cc: back within a second of a restart.
        self._channel = grpc.insecure_channel(self.address, options=[
            ("grpc.initial_reconnect_backoff_ms", 100),
            ("grpc.min_reconnect_backoff_ms", 100),
            ("grpc.max_reconnect_backoff_ms", 1000),
            ("grpc.max_receive_message_length", MAX_MESSAGE_BYTES),
            ("grpc.max_send_message_length", MAX_MESSAGE_BYTES),
        ])
        self._jobs = service_pb2_grpc.JobServiceStub(self._channel)

    def close(self):
        self._channel.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # -- calls --------------------------------------------------------------------------------

    def _call(self, method, request, what):
        try:
            return method(request, timeout=self.timeout, metadata=self._metadata)
        except grpc.RpcError as e:
            raise from_rpc_error(e, what, self.address) from None

    def submit(self, case, request_id=None, study=None):
        """Submits a case (a path to a .textproto file, or a sphd.Case) and returns the Job.

        request_id: the idempotency key (default: a random one); submitting again with the same
        key returns the job created the first time. study: a sphd.StudySpec for a convergence
        study (see study()). Retries for 30 s while the server is unreachable, as sphctl.
        """
        if isinstance(case, (str, os.PathLike)):
            what = str(case)
            case = load_case(case)
        elif isinstance(case, case_pb2.Case):
            what = case.name or "case"
        else:
            raise TypeError("submit needs a path or a sphd.Case, not " + type(case).__name__)
        text = str(case)  # text format, what sphctl sends
        if len(text.encode()) > MAX_CASE_TEXT_BYTES:
            raise SphdError(f"{what}: case_text: the case is {len(text) >> 20} MiB with its point "
                            f"and reference data inlined; the service takes at most "
                            f"{MAX_CASE_TEXT_BYTES >> 20} MiB", None)
        req = service_pb2.SubmitRequest(request_id=request_id or _random_request_id(),
                                        case_text=text)
        if study is not None:
            req.study.CopyFrom(study)
        give_up = time.monotonic() + SUBMIT_RETRY_SECONDS
        pause = 0.2
        while True:
            try:
                return self._jobs.Submit(req, timeout=self.timeout,
                                         metadata=self._metadata).job
            except grpc.RpcError as e:
                err = from_rpc_error(e, ("study " if study else "submit ") + what, self.address)
                if not isinstance(err, Unavailable) or time.monotonic() >= give_up:
                    raise err from None
            time.sleep(pause)
            pause = min(pause * 2, 3.0)

    def study(self, case, refine=None, ratio=None, dx=None, request_id=None):
        """A convergence study of the case (it needs a reference): `refine` levels at dx, dx /
        ratio, ... (ratio default sqrt(2)), or the spacings listed in `dx`. Returns the Job; its
        result holds study.csv, study.md, study.png and level_<k>/result.h5 (docs/accuracy.md).
        """
        if (refine is None) == (dx is None):
            raise ValueError("study needs refine=N or dx=[...], not both")
        spec = study_pb2.StudySpec()
        if refine is not None:
            spec.refine = refine
            if ratio is not None:
                spec.ratio = ratio
        else:
            spec.dx.extend(dx)
        return self.submit(case, request_id=request_id, study=spec)

    def status(self, job_id, include_case=False):
        """The Job with its attempts (and its canonical case text with include_case)."""
        return self._call(self._jobs.GetJob,
                          service_pb2.GetJobRequest(job_id=job_id, include_case=include_case),
                          "status " + job_id)

    def list(self, states=(), limit=50):
        """Jobs, newest first, optionally only in `states` (JobState values or names such as
        'RUNNING'); limit 0 lists all."""
        req = service_pb2.ListJobsRequest(states=[_state(s) for s in states])
        jobs = []
        while True:
            if limit > 0:
                req.page_size = min(limit - len(jobs), 1000)
            page = self._call(self._jobs.ListJobs, req, "list")
            jobs.extend(page.jobs)
            if not page.next_page_token or (limit > 0 and len(jobs) >= limit):
                return jobs
            req.page_token = page.next_page_token

    def watch(self, job_id, after_sequence=0):
        """The job's events (sphd.JobEvent) from after `after_sequence`, live, ending after the
        event that puts the job in a terminal state. While the server is away (a restart) it
        reconnects and resumes after the last event seen, for up to 120 s, as sphctl watch."""
        last = after_sequence
        outage_since = None
        pause = 0.2
        while True:
            stream = self._jobs.WatchJob(
                service_pb2.WatchJobRequest(job_id=job_id, after_sequence=last),
                metadata=self._metadata)
            try:
                for event in stream:
                    outage_since = None
                    pause = 0.2
                    last = event.sequence
                    yield event
                return
            except grpc.RpcError as e:
                err = from_rpc_error(e, "watch " + job_id, self.address)
                if not isinstance(err, Unavailable):
                    raise err from None
                now = time.monotonic()
                if outage_since is None:
                    outage_since = now
                elif now - outage_since > WATCH_RECONNECT_SECONDS:
                    raise err from None
            finally:
                stream.cancel()
            time.sleep(pause)
            pause = min(pause * 2, 2.0)

    def wait(self, job_id, on_event=None):
        """Follows the job to its end (watch) and returns the final Job; raises JobFailed or
        JobCancelled when it did not succeed. on_event(event) sees every event on the way."""
        for event in self.watch(job_id):
            if on_event is not None:
                on_event(event)
        job = self.status(job_id)
        if job.state == service_pb2.JOB_STATE_FAILED:
            raise JobFailed(f"{job_id} failed: {job.reason}", job)
        if job.state == service_pb2.JOB_STATE_CANCELLED:
            raise JobCancelled(f"{job_id} was cancelled: {job.reason}", job)
        return job

    def cancel(self, job_id, reason=""):
        """Cancels the job (idempotent): a queued job at once, a running one at its next step
        boundary. Returns the Job."""
        return self._call(self._jobs.CancelJob,
                          service_pb2.CancelJobRequest(job_id=job_id, reason=reason),
                          "cancel " + job_id)

    def logs(self, job_id, attempt=0, follow=False, after_sequence=0):
        """The worker pool's log lines for the job (sphd.service_pb2.LogLine: attempt,
        sequence, time_unix_ms, text), oldest first, of one attempt or all (0). With follow,
        new lines as they come until the job ends, like `sphctl logs --follow`."""
        req = service_pb2.GetJobLogsRequest(job_id=job_id, attempt=attempt,
                                            after_sequence=after_sequence)
        outage_since = None
        while True:
            try:
                page = self._jobs.GetJobLogs(req, timeout=self.timeout, metadata=self._metadata)
            except grpc.RpcError as e:
                err = from_rpc_error(e, "logs " + job_id, self.address)
                now = time.monotonic()
                if not follow or not isinstance(err, Unavailable):
                    raise err from None
                if outage_since is None:
                    outage_since = now
                elif now - outage_since > WATCH_RECONNECT_SECONDS:
                    raise err from None
                time.sleep(1)
                continue
            outage_since = None
            for line in page.lines:
                req.after_sequence = line.sequence
                yield line
            if page.lines:
                continue
            if not follow or is_terminal(page.state):
                return
            time.sleep(0.5)

    def fetch(self, job_id, dir=None, file=None):
        """Downloads the job's result files (or only `file`) into `dir` (default: the job id),
        checking each file's size and sha256 against the manifest; returns the paths written.
        A file is written as NAME.part and renamed once verified; VerifyFailed otherwise."""
        job = self.status(job_id)
        if not job.HasField("result") or not job.result.files:
            raise Conflict(f"fetch {job_id}: no result yet ({job.reason})")
        dir = job.id if dir is None else os.fspath(dir)
        paths = []
        for f in job.result.files:
            if file is not None and f.name != file:
                continue
            parts = f.name.split("/")
            if not f.name or os.path.isabs(f.name) or ".." in parts:
                raise VerifyFailed(f"refusing manifest entry '{f.name}' (outside {dir})")
            dest = os.path.join(dir, *parts)
            self._fetch_file(job.id, f, dest)
            paths.append(dest)
        if not paths:
            raise NotFound(f"fetch {job.id} {file}: no such file in the result manifest")
        return paths

    def _fetch_file(self, job_id, f, dest):
        os.makedirs(os.path.dirname(dest) or ".", exist_ok=True)
        part = dest + ".part"
        digest = hashlib.sha256()
        offset = 0
        with open(part, "wb") as out:
            for attempt in range(FETCH_RETRIES + 1):
                req = service_pb2.FetchResultRequest(job_id=job_id, file=f.name, offset=offset)
                try:
                    for chunk in self._jobs.FetchResult(req, metadata=self._metadata):
                        if chunk.offset != offset:
                            raise VerifyFailed(f"{f.name}: chunk at offset {chunk.offset}, "
                                               f"expected {offset}")
                        out.write(chunk.data)
                        digest.update(chunk.data)
                        offset += len(chunk.data)
                    break
                except grpc.RpcError as e:
                    err = from_rpc_error(e, f"fetch {job_id} {f.name}", self.address)
                    if not isinstance(err, Unavailable) or attempt == FETCH_RETRIES:
                        out.close()
                        os.remove(part)
                        raise err from None
                    time.sleep(0.5)
        hexdigest = digest.hexdigest()
        if offset != f.size or hexdigest != f.sha256:
            os.remove(part)
            raise VerifyFailed(f"{f.name} failed verification: {offset} bytes, sha256 "
                               f"{hexdigest}; the manifest says {f.size} bytes, sha256 {f.sha256}")
        os.replace(part, dest)


def _read_token(path):
    try:
        with open(path, encoding="utf-8") as f:
            token = f.readline().strip()
    except OSError:
        raise SphdError(f"cannot read token file '{path}'") from None
    if not token:
        raise SphdError(f"token file '{path}' is empty")
    return token


def _random_request_id():
    return "sphd-py-" + secrets.token_hex(12)


def _state(s):
    if isinstance(s, str):
        name = s.upper()
        try:
            return service_pb2.JobState.Value(name if name.startswith("JOB_STATE_")
                                              else "JOB_STATE_" + name)
        except ValueError:
            raise ValueError(f"unknown state '{s}' (QUEUED, RUNNING, SUCCEEDED, FAILED, "
                             "CANCELLED)") from None
    return s
