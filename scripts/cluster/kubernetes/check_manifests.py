#!/usr/bin/env python3
"""Checks the Kubernetes route without a cluster: parses results-volume.yaml, sweep-job.yaml,
merge-job.yaml and the Dockerfile, checks the fields the Jobs need (an Indexed Job whose
completions equal the shard count, the shard index from JOB_COMPLETION_INDEX, --resume, one
ReadWriteMany volume shared by both Jobs, a debian:12 image built by the project's install
script), then runs the Jobs' own command lines with /bin/sh as the pods would (every index of
the sweep, then the merge) on a small scenario and compares the merged frames.csv with a
local sweep's, byte for byte.

    check_manifests.py MARKERBENCH_BINARY
"""
import os
import shutil
import subprocess
import sys
import tempfile

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", ".."))


def fail(message):
    print("check_manifests: " + message, file=sys.stderr)
    sys.exit(1)


def expect(condition, message):
    if not condition:
        fail(message)


def load(name):
    with open(os.path.join(HERE, name)) as f:
        documents = [d for d in yaml.safe_load_all(f) if d is not None]
    expect(len(documents) == 1, f"{name}: expected one document, found {len(documents)}")
    return documents[0]


def only_container(job, name):
    containers = job["spec"]["template"]["spec"]["containers"]
    expect(len(containers) == 1, f"{name}: expected one container")
    return containers[0]


def env_of(container):
    return {e["name"]: e.get("value") for e in container.get("env", [])}


def results_mount(job, container, claim, name):
    """The mount path of the shared claim in the Job's container."""
    volumes = {v["name"]: v for v in job["spec"]["template"]["spec"].get("volumes", [])}
    for mount in container.get("volumeMounts", []):
        volume = volumes.get(mount["name"], {})
        if volume.get("persistentVolumeClaim", {}).get("claimName") == claim:
            return mount["mountPath"]
    fail(f"{name}: no volume mount of the claim {claim}")


def shell_line(container, name):
    expect(container.get("command") == ["/bin/sh", "-c"], f"{name}: expected /bin/sh -c")
    expect(len(container.get("args", [])) == 1, f"{name}: expected one shell line in args")
    return container["args"][0]


def main():
    if len(sys.argv) != 2:
        fail("usage: check_manifests.py MARKERBENCH_BINARY")
    binary = os.path.abspath(sys.argv[1])

    volume = load("results-volume.yaml")
    expect(volume["kind"] == "PersistentVolumeClaim", "results-volume.yaml: expected a PVC")
    expect("ReadWriteMany" in volume["spec"]["accessModes"],
           "results-volume.yaml: the shards' pods write at once: expected ReadWriteMany")
    claim = volume["metadata"]["name"]

    sweep = load("sweep-job.yaml")
    expect(sweep["apiVersion"] == "batch/v1" and sweep["kind"] == "Job", "sweep-job.yaml: a Job")
    spec = sweep["spec"]
    expect(spec.get("completionMode") == "Indexed", "sweep-job.yaml: completionMode: Indexed")
    shards = spec["completions"]
    expect(isinstance(shards, int) and shards >= 1, "sweep-job.yaml: completions >= 1")
    expect(1 <= spec.get("parallelism", 1) <= shards, "sweep-job.yaml: parallelism")
    expect(spec["template"]["spec"]["restartPolicy"] in ("OnFailure", "Never"),
           "sweep-job.yaml: restartPolicy")
    sweep_container = only_container(sweep, "sweep-job.yaml")
    sweep_env = env_of(sweep_container)
    expect(sweep_env.get("MARKERBENCH_SHARDS") == str(shards),
           f"sweep-job.yaml: MARKERBENCH_SHARDS must equal completions ({shards})")
    sweep_mount = results_mount(sweep, sweep_container, claim, "sweep-job.yaml")
    sweep_line = shell_line(sweep_container, "sweep-job.yaml")
    for needed in ("--shard ${JOB_COMPLETION_INDEX}/${MARKERBENCH_SHARDS}", "--resume",
                   f"--out {sweep_mount}/shard-${{JOB_COMPLETION_INDEX}}"):
        expect(needed in sweep_line, f"sweep-job.yaml: the command needs '{needed}'")
    for scenario in sweep_env["SCENARIOS"].split():
        expect(os.path.isfile(os.path.join(ROOT, scenario)),
               f"sweep-job.yaml: SCENARIOS: {scenario} is not in the image")

    merge = load("merge-job.yaml")
    merge_container = only_container(merge, "merge-job.yaml")
    expect(env_of(merge_container).get("MARKERBENCH_SHARDS") == str(shards),
           "merge-job.yaml: MARKERBENCH_SHARDS must equal the sweep's completions")
    expect(merge_container["image"] == sweep_container["image"], "merge-job.yaml: image")
    merge_mount = results_mount(merge, merge_container, claim, "merge-job.yaml")
    merge_line = shell_line(merge_container, "merge-job.yaml")

    with open(os.path.join(HERE, "Dockerfile")) as f:
        dockerfile = f.read().splitlines()
    instructions = [line for line in dockerfile if line and not line.startswith("#")]
    expect(instructions[0] == "FROM debian:12", "Dockerfile: FROM debian:12")
    expect(any("scripts/install-deps.sh" in line for line in instructions),
           "Dockerfile: install with scripts/install-deps.sh")
    workdir = [line.split()[1] for line in instructions if line.startswith("WORKDIR")]
    copy = [line.split() for line in instructions if line.startswith("COPY")]
    expect(copy and copy[0][1] == "." and workdir and workdir[0] == copy[0][2],
           "Dockerfile: the repository copied to the WORKDIR (scenario paths are relative)")
    expect(any("build/bench" in line for line in instructions if line.startswith("ENV PATH")),
           "Dockerfile: markerbench on PATH")

    # The pods' command lines, run here: /results becomes a temporary folder, markerbench the
    # binary under test, the scenarios a small one.
    work = tempfile.mkdtemp(prefix="markerbench_k8s.")
    try:
        bin_dir = os.path.join(work, "bin")
        os.makedirs(bin_dir)
        os.symlink(binary, os.path.join(bin_dir, "markerbench"))
        results = os.path.join(work, "results")
        env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ["PATH"])
        env.update({k: v for k, v in sweep_env.items() if v is not None})
        env["SCENARIOS"] = "scenarios/smoke.yaml"
        for index in range(shards):
            env["JOB_COMPLETION_INDEX"] = str(index)
            subprocess.run(["/bin/sh", "-c", sweep_line.replace(sweep_mount, results)],
                           cwd=ROOT, env=env, check=True, stderr=subprocess.DEVNULL)
        subprocess.run(["/bin/sh", "-c", merge_line.replace(merge_mount, results)],
                       cwd=ROOT, env=env, check=True)
        subprocess.run([binary, "sweep", "scenarios/smoke.yaml", "--out",
                        os.path.join(work, "local")], cwd=ROOT, check=True,
                       stderr=subprocess.DEVNULL)
        with open(os.path.join(results, "merged", "smoke", "frames.csv"), "rb") as f:
            merged = f.read()
        with open(os.path.join(work, "local", "smoke", "frames.csv"), "rb") as f:
            local = f.read()
        expect(merged == local, "the merged frames.csv differs from the local sweep's")
    finally:
        shutil.rmtree(work)
    print(f"check_manifests: the manifests hold together; {shards} shards merged to the local "
          "sweep's bytes")


if __name__ == "__main__":
    main()
