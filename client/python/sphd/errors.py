"""The errors the client raises: one class per sphctl exit code (docs/service.md), so a script
handles a failure the way it would handle sphctl's exit status. Each carries `exit_code` (the
code sphctl would exit with) and, for server errors, the gRPC `code`."""
import grpc


class SphdError(Exception):
    exit_code = 1

    def __init__(self, message, code=None):
        super().__init__(message)
        self.code = code


class InvalidCase(SphdError):
    exit_code = 3


class NotFound(SphdError):
    exit_code = 4


class Unavailable(SphdError):
    exit_code = 5


class AuthError(SphdError):
    exit_code = 6


class VerifyFailed(SphdError):
    exit_code = 7


class Conflict(SphdError):
    exit_code = 8


class JobFailed(SphdError):
    """Client.wait: the job ended FAILED (`job` holds it, `job.reason` says why)."""
    exit_code = 10

    def __init__(self, message, job=None):
        super().__init__(message)
        self.job = job


class JobCancelled(JobFailed):
    exit_code = 11


_BY_CODE = {
    grpc.StatusCode.INVALID_ARGUMENT: InvalidCase,
    grpc.StatusCode.NOT_FOUND: NotFound,
    grpc.StatusCode.UNAVAILABLE: Unavailable,
    grpc.StatusCode.DEADLINE_EXCEEDED: Unavailable,
    grpc.StatusCode.UNAUTHENTICATED: AuthError,
    grpc.StatusCode.PERMISSION_DENIED: AuthError,
    grpc.StatusCode.ALREADY_EXISTS: Conflict,
    grpc.StatusCode.FAILED_PRECONDITION: Conflict,
    grpc.StatusCode.DATA_LOSS: VerifyFailed,
}


def from_rpc_error(error, what, address):
    """The SphdError for a grpc.RpcError, worded like sphctl's message."""
    code = error.code()
    hint = ""
    if code == grpc.StatusCode.UNAVAILABLE:
        hint = f" (is sph-server running at {address}? see SPHCTL_SERVER)"
    elif code == grpc.StatusCode.UNAUTHENTICATED:
        hint = " (see token_file / SPHCTL_TOKEN_FILE)"
    cls = _BY_CODE.get(code, SphdError)
    return cls(f"{what}: {error.details()}{hint}", code)
