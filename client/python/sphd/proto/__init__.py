"""The protobuf and gRPC stubs of proto/sph/v1/ (case_pb2, study_pb2, service_pb2,
service_pb2_grpc). They are generated at build time by the CMake target `sphd_python` (protoc
and grpc_python_plugin) into the staged package build/python/sphd/proto/, never committed: use
the package from there (PYTHONPATH=build/python, or pip install build/python)."""
