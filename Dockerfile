# One image for every DCS program: dcs-coordinator, dcs-learner, dcs-actor, and the dcs client
# with dcs-train beside it. Two stages: the sources built with
# Debian 12's -dev packages, then a slim runtime with only the libraries the programs load, run
# as a non-root user under tini. Without arguments it runs the coordinator; docker-compose.yml
# runs each program from it.
#
#   docker build -t dcs:latest .
#   docker run --rm dcs:latest dcs version
#
# The build runs no tests (`make test` does, outside containers) and takes as long as the
# programs' part of `make build` (README.md: libtorch's headers dominate).

# ---- build: the five programs, from the sources, with Debian's -dev packages -----------------
FROM debian:bookworm AS build

# scripts/bootstrap's list without ccache, git, prometheus, chromium and gnuplot (tests, reports
# and caches, not the build). GoogleTest and Google Benchmark stay: cmake/dependencies.cmake
# finds them even when tests and benchmarks are off.
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
      build-essential cmake ninja-build pkg-config \
      libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler grpc-proto \
      libabsl-dev prometheus-cpp-dev libcpp-httplib-dev libcurl4-openssl-dev libssl-dev \
      libyaml-cpp-dev libcli11-dev \
      libtorch-dev libeigen3-dev libbox2d-dev libsqlite3-dev libsqlitecpp-dev libpng-dev \
      libboost-math-dev \
      libgtest-dev libgmock-dev libbenchmark-dev \
 && rm -rf /var/lib/apt/lists/*

WORKDIR /src
COPY . .
# No git history in the build context (.dockerignore), so `dcs version` names the commit as
# "unknown". The CMake project has no install rules: the programs are copied from where every
# program is built (build/services/, where `dcs` expects dcs-train beside it).
RUN cmake -S . -B /build -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DDCS_BUILD_TESTS=OFF -DDCS_BUILD_BENCHMARKS=OFF \
 && cmake --build /build --target dcs dcs-train dcs-coordinator dcs-learner dcs-actor \
 && install -d /opt/dcs/bin \
 && install -m 0755 -s /build/services/dcs /build/services/dcs-train \
      /build/services/dcs-coordinator /build/services/dcs-learner /build/services/dcs-actor \
      /opt/dcs/bin/

# ---- runtime: the programs and the libraries they load ----------------------------------------
FROM debian:bookworm-slim

# The packages of the sonames the programs link (readelf -d, then dpkg -S), plus: tini (PID 1),
# OpenBLAS's pthread build behind libtorch (as scripts/bootstrap installs it: 1.7x faster PPO
# updates, safe from several threads), gnuplot for `dcs plot`, CA certificates.
RUN apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
      tini ca-certificates \
      libabsl20220623 libgrpc29 libgrpc++1.51 libprotobuf32 libprometheus-cpp-core1.0 \
      libcpp-httplib0.11 libssl3 libyaml-cpp0.7 libsqlite3-0 libpng16-16 libbox2d2 \
      libtorch1.13 libopenblas0-pthread gnuplot-nox \
 && rm -rf /var/lib/apt/lists/*

# A system user with a fixed uid (10001), owning the data directory; the coordinator keeps its
# store in /var/lib/dcs/coordinator (a volume in docker-compose.yml, which starts out owned by
# this user because the directory exists in the image).
RUN groupadd --system --gid 10001 dcs \
 && useradd --system --uid 10001 --gid dcs --home-dir /var/lib/dcs --no-create-home \
      --shell /usr/sbin/nologin dcs \
 && install -d -o dcs -g dcs /var/lib/dcs /var/lib/dcs/coordinator

COPY --from=build /opt/dcs/bin/ /opt/dcs/bin/
# The example configs and sweep specs, to submit from inside a container:
#   docker-compose exec coordinator dcs submit /usr/share/dcs/configs/quickstart.yaml --watch
COPY --from=build /src/configs/ /usr/share/dcs/configs/
ENV PATH=/opt/dcs/bin:$PATH
WORKDIR /var/lib/dcs
USER dcs:dcs

# gRPC: coordinator 50051, learner 50052, actor 50053 (docker-compose.yml's ports); every
# process serves /metrics on 9464.
EXPOSE 50051 50052 50053 9464

# SERVING is the coordinator's default command's health; docker-compose.yml gives each program
# its own check (a worker is SERVING only while registered with the coordinator).
HEALTHCHECK --interval=5s --timeout=3s --start-period=10s --retries=5 \
  CMD ["dcs", "--timeout", "2s", "health", "--addr", "127.0.0.1:50051"]

# tini forwards SIGTERM to the program (which drains and exits 0) and reaps zombies.
ENTRYPOINT ["/usr/bin/tini", "--"]
CMD ["dcs-coordinator", "--listen", "0.0.0.0:50051", "--metrics-listen", "0.0.0.0:9464", \
     "--data-dir", "/var/lib/dcs/coordinator", "--log-format", "json"]
