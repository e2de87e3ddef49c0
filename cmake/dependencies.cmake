# Every third-party dependency, found once, from Debian 12 packages (scripts/bootstrap).
find_package(absl CONFIG REQUIRED)
find_package(Protobuf REQUIRED)
find_package(gRPC CONFIG REQUIRED)
find_package(prometheus-cpp CONFIG REQUIRED)
# prometheus-cpp's CMake package has no version file; its pkg-config file has the version.
find_package(PkgConfig REQUIRED)
pkg_check_modules(PROMETHEUS_CPP_CORE REQUIRED prometheus-cpp-core)
# cpp-httplib serves /metrics (services/metrics_endpoint.h says why not prometheus-cpp's pull).
pkg_check_modules(CPP_HTTPLIB REQUIRED IMPORTED_TARGET cpp-httplib)
find_package(Torch CONFIG REQUIRED)
find_package(Eigen3 CONFIG REQUIRED)
find_package(box2d CONFIG REQUIRED)
find_package(SQLite3 REQUIRED)
find_package(SQLiteCpp CONFIG REQUIRED)
find_package(yaml-cpp CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json 3 CONFIG REQUIRED)
find_package(CURL REQUIRED)
find_package(OpenSSL REQUIRED)
find_package(PNG REQUIRED)
find_package(GTest CONFIG REQUIRED)
find_package(benchmark CONFIG REQUIRED)

# The standard gRPC protos (health, reflection) ship as sources in Debian's grpc-proto.
find_path(DCS_GRPC_PROTO_DIR grpc/health/v1/health.proto
          PATHS /usr/share/grpc-proto REQUIRED)
