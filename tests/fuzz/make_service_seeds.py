#!/usr/bin/env python3
"""Writes the seed corpora of the fuzzers fed protobuf messages: coordinator_service_fuzzer's
(one valid call of every method, as fuzzed_call.h encodes a call: the method's index in its
service, then the request, or length-prefixed requests for a client-streaming method) and
data_plane_fuzzer's (a rollout streamed in pieces, policies). Messages are written as text
protos and encoded by protoc, so the seeds follow the .proto files. Run from the repository's root after changing the protos:

    tests/fuzz/make_service_seeds.py
"""
import hashlib
import pathlib
import re
import struct
import subprocess

ROOT = pathlib.Path(__file__).resolve().parents[2]
PROTO_DIR = ROOT / "proto"
CORPUS = ROOT / "tests" / "fuzz" / "corpus"


def read(path):
    return (ROOT / path).read_text()


def quoted(text):
    """A text-proto string literal of `text`."""
    return '"' + text.encode("unicode_escape").decode("ascii").replace('"', '\\"') + '"'


def encode(proto_file, message, text):
    return subprocess.run(
        ["protoc", f"--encode=dcs.v1.{message}", f"-I{PROTO_DIR}", "-I/usr/include",
         str(PROTO_DIR / proto_file)],
        input=text.encode(), capture_output=True, check=True).stdout


def methods(proto_file, service):
    """(name, request type, client streaming) of each method, in the descriptor's order."""
    body = read(f"proto/{proto_file}").split(f"service {service} {{", 1)[1].split("\n}", 1)[0]
    return [(m[0], m[2], bool(m[1])) for m in
            re.findall(r"rpc (\w+)\((stream )?(\w+)\)", body)]


def write_corpus(target, proto_file, service, calls):
    """`calls`: method name -> list of calls, each a list of text-proto requests."""
    directory = CORPUS / target
    directory.mkdir(parents=True, exist_ok=True)
    for old in directory.iterdir():
        old.unlink()
    listed = methods(proto_file, service)
    missing = {name for name, _, _ in listed} - set(calls)
    if missing:
        raise SystemExit(f"{service}: no seed for {sorted(missing)}")
    for index, (name, request_type, streaming) in enumerate(listed):
        for number, requests in enumerate(calls[name]):
            data = bytes([index])
            for text in requests:
                encoded = encode(proto_file, request_type, text)
                if streaming:
                    data += len(encoded).to_bytes(2, "little")
                data += encoded
            (directory / f"{name}_{number}").write_bytes(data)


def coordinator_calls():
    run_config = read("configs/cartpole_default_static.yaml")
    sweep_spec = read("configs/quickstart.yaml")
    space = read("bench/study/branin.yaml")
    run_state = read("tests/fuzz/corpus/checkpoint_fuzzer/step64_two_evaluations.txt").split(
        "\n", 1)[1]
    learner = "learner state"
    lease = 'lease {run_id: "run-1" slot: -1 epoch: 1}'
    piece = (f'checkpoint {{name: "000000000064" '
             f'learner_sha256: "{hashlib.sha256(learner.encode()).hexdigest()}" '
             f'run_state_sha256: "{hashlib.sha256(run_state.encode()).hexdigest()}" '
             f'learner: {quoted(learner)} run_state: {quoted(run_state)}}}')
    return {
        "RegisterWorker": [['worker {role: WORKER_ROLE_LEARNER address: "127.0.0.1:6000" '
                            'hostname: "fuzz" pid: 42}'],
                           ['worker {role: WORKER_ROLE_ACTOR address: "127.0.0.1:6001"}']],
        "Heartbeat": [['worker_id: "learner-1"']],
        "UnregisterWorker": [['worker_id: "actor-1"']],
        "GetClusterStatus": [[""]],
        "SubmitRun": [[f'request_id: "run-a" config: {quoted(run_config)} '
                       'config_name: "cartpole_default_static.yaml" seed: 3']],
        "GetRun": [['run_id: "run-1"']],
        "ListRuns": [[""]],
        "CancelRun": [['run_id: "run-1"']],
        "GetRunFiles": [['run_id: "run-1"']],
        "BackupStore": [[""]],
        "WatchRun": [['run_id: "run-1"']],
        "WatchSweep": [['sweep_id: "sweep-1"']],
        "DeleteRuns": [['run_ids: "run-1"'], ['run_ids: ["run-2", "run-1", "run-2"]']],
        "DeleteSweeps": [['sweep_ids: "sweep-1"']],
        "ListStudies": [[""]],
        "SubmitSweep": [[f'request_id: "sweep-a" spec: {quoted(sweep_spec)} '
                         'spec_name: "quickstart.yaml" name: "quickstart"'],
                        [f'request_id: "sweep-b" spec: {quoted(sweep_spec)} validate_only: true']],
        "GetSweep": [['sweep_id: "sweep-1"']],
        "ListSweeps": [[""]],
        "CancelSweep": [['sweep_id: "sweep-1"']],
        "RetrySweep": [['sweep_id: "sweep-1"']],
        "GetSweepResults": [['sweep_id: "sweep-1"'], ['sweep_id: "sweep-1" scores_only: true']],
        "CreateStudy": [[f'request_id: "study-a" study {{name: "branin" space: {quoted(space)} '
                         'sampler: "tpe" seed: 1 direction: "minimize" '
                         'pruner {kind: "median"}}']],
        "GetStudy": [['study_id: "study-1"']],
        "AskTrial": [['study_id: "study-1" request_id: "ask-a"']],
        "TellTrial": [['study_id: "study-1" number: 0 state: "complete" value: 1.5']],
        "ReportTrial": [['study_id: "study-1" number: 0 step: 10 value: 2.5']],
        "AcquireRun": [['holder: "learner-1" address: "127.0.0.1:6000" numerics: "fingerprint"']],
        "AcquireSlot": [['holder: "actor-1" numerics: "fingerprint" '
                         'complete_learners {run_id: "run-2" slot: -1 epoch: 1}']],
        "RenewLease": [[lease]],
        "ReleaseLease": [['lease {run_id: "run-1" slot: 0 epoch: 1}']],
        "ReportProgress": [[f'{lease} progress {{timesteps: 64 total_timesteps: 150000 '
                            'policy_version: 1 steps_per_second: 900 recent_return: 20}']],
        "PutCheckpoint": [[f'{lease} {piece} evaluation_log: ""']],
        "FinishRun": [[f'{lease} state: RUN_STATE_COMPLETED'],
                      [f'{lease} state: RUN_STATE_FAILED error: "diverged"']],
        "GetCheckpoint": [[lease]],
        "SubmitEvaluation": [[f'{lease} policy_version: 1 step: 64 contexts: 2 episodes: 2 '
                              'weights: "policy"']],
        "GetEvaluation": [['run_id: "run-1" policy_version: 1']],
        "AcquireEvaluation": [['holder: "actor-1" numerics: "fingerprint" max_jobs: 2']],
        "ReportEvaluation": [['results {job {run_id: "run-1" policy_version: 1 context: 0 '
                              'epoch: 1} result {returns: [12, 30] seconds: 0.01}}']],
        "SubmitGridEvaluation": [['request_id: "grid-1" run_id: "run-1" grid {axes {feature: '
                                  '"length" low: 0.2 high: 1.2 count: 3} seed: 5} episodes: 2 '
                                  'weights: "policy"']],
    }


def float32s(*values):
    return "".join(f"\\{b:03o}" for b in struct.pack(f"<{len(values)}f", *values))


def tensor(dims, *values):
    shape = " ".join(f"shape: {d}" for d in dims)
    return f'{{dtype: D_TYPE_FLOAT32 {shape} data: "{float32s(*values)}"}}'


def data_plane_seeds():
    """data_plane_fuzzer's inputs: a CartPole-sized rollout in two pieces, and policies."""
    rollout = encode("dcs/v1/trajectory.proto", "SlotRollout",
                     f"slot: 0 num_steps: 2 inputs {tensor([2, 4], *range(8))} "
                     f"actions {tensor([2, 1], 0, 1)} rewards {tensor([2], 1, 1)} "
                     'episode_starts {dtype: D_TYPE_UINT8 shape: 2 data: "\\001\\000"} '
                     f"last_input {tensor([4], 0.1, 0.2, 0.3, 0.4)} "
                     "finished {episode_return: 12 length: 12 step: 1} "
                     f"journal {{episode: 3 reset_step: 10 actions {tensor([1, 1], 1)} "
                     "episode_return: 1}")
    half = len(rollout) // 2
    stream = b""
    for index, piece in enumerate([rollout[:half], rollout[half:]]):
        header = 'lease {run_id: "run-1" slot: 0 epoch: 1} learner_epoch: 1 ' if index == 0 else ""
        message = encode("dcs/v1/learner_service.proto", "PushRolloutRequest",
                         f"{header}data: {quoted_bytes(piece)}")
        stream += len(message).to_bytes(2, "little") + message
    discrete = encode("dcs/v1/trajectory.proto", "PolicyWeights",
                      f"layers {{weight {tensor([2, 4], *range(8))} bias {tensor([2], 0, 0)} "
                      "activation: ACTIVATION_NONE} num_actions: 2")
    continuous = encode("dcs/v1/trajectory.proto", "PolicyWeights",
                        f"layers {{weight {tensor([3, 4], *range(12))} bias {tensor([3], 0, 0, 0)} "
                        "activation: ACTIVATION_TANH} "
                        f"layers {{weight {tensor([1, 3], 1, 2, 3)} bias {tensor([1], 0)} "
                        f"activation: ACTIVATION_NONE}} log_std {tensor([1], -0.5)}")
    directory = CORPUS / "data_plane_fuzzer"
    directory.mkdir(parents=True, exist_ok=True)
    for old in directory.iterdir():
        old.unlink()
    (directory / "rollout_in_two_pieces").write_bytes(b"\x00" + stream)
    (directory / "policy_discrete").write_bytes(b"\x01" + discrete)
    (directory / "policy_continuous").write_bytes(b"\x01" + continuous)


def quoted_bytes(data):
    return '"' + "".join(f"\\{b:03o}" for b in data) + '"'


write_corpus("coordinator_service_fuzzer", "dcs/v1/coordinator_service.proto",
             "CoordinatorService", coordinator_calls())
data_plane_seeds()
