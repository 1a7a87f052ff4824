"""sphd from Python: submit and follow jobs on sph-server, read result.h5 files.

    import sphd
    client = sphd.Client()                      # $SPHCTL_SERVER, $SPHCTL_TOKEN_FILE as sphctl
    job = client.submit("cases/dambreak_2d.textproto")
    for event in client.watch(job.id): ...
    client.fetch(job.id, "out")
    result = sphd.Result("out/result.h5")

See docs/python.md.
"""
from sphd.case_file import load_case, parse_case
from sphd.client import Client, is_terminal, state_name
from sphd.errors import (AuthError, Conflict, InvalidCase, JobCancelled, JobFailed, NotFound,
                         SphdError, Unavailable, VerifyFailed)
from sphd.proto import case_pb2, service_pb2, study_pb2
from sphd.result import Result, Snapshot

Case = case_pb2.Case
Job = service_pb2.Job
JobEvent = service_pb2.JobEvent
JobState = service_pb2.JobState
StudySpec = study_pb2.StudySpec

__all__ = [
    "AuthError", "Case", "Client", "Conflict", "InvalidCase", "Job", "JobCancelled", "JobEvent",
    "JobFailed", "JobState", "NotFound", "Result", "Snapshot", "SphdError", "StudySpec",
    "Unavailable", "VerifyFailed", "case_pb2", "load_case", "parse_case", "service_pb2",
    "is_terminal", "state_name", "study_pb2",
]
