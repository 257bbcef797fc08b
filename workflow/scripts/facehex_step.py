"""One step of one patient in the cohort workflow (workflow/Snakefile, run by its `script:` directive).

Runs the step's facehex commands and writes the patient's status file (format in core/workflow/cohort.h) whatever
they do: the steps so far, each with its exit code, its error line, its wall time and the Slurm job it ran in. A failed
patient is thus a finished job with its failure recorded, and the cohort goes on; a step after a failed one runs
nothing and passes the failure on. The commands' output goes to the step's log.
"""
import collections
import json
import os
import shlex
import signal
import subprocess
import time

STATUS_FORMAT, STATUS_VERSION = "facehex-cohort-status", 1


def error_line(tail, exit_code):
    """The line that says why: facehex's one-line error, or its warning about inverted cells (exit code 3)."""
    for prefix in ("error:", "warning:"):
        lines = [line.strip() for line in tail if line.startswith(prefix)]
        if lines:
            return lines[-1]
    if exit_code < 0:
        return f"killed by {signal.Signals(-exit_code).name}"
    last = [line.strip() for line in tail if line.strip()]
    return last[-1] if last else f"exit code {exit_code}"


def run(commands, log_path):
    """(exit code, error line) of the first command that fails, else (0, "")."""
    with open(log_path, "w") as log:
        for command in commands:
            log.write("$ " + shlex.join(command) + "\n")
            log.flush()
            tail = collections.deque(maxlen=50)
            try:
                process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                           errors="replace")
            except OSError as e:
                return 127, f"cannot run {command[0]}: {e.strerror}"
            for line in process.stdout:
                log.write(line)
                tail.append(line.split("\r")[-1])
            code = process.wait()
            if code != 0:
                return code, error_line(tail, code)
    return 0, ""


def write_json(path, document):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(document, f, indent=2)
        f.write("\n")
    os.replace(tmp, path)


def main(sm):
    steps = []
    if "after" in sm.input.keys():
        with open(sm.input.after) as f:
            steps = json.load(f)["steps"]
    if all(step["exit_code"] == 0 for step in steps):
        os.makedirs(sm.params.folder, exist_ok=True)
        start = time.monotonic()
        exit_code, error = run(sm.params.commands, sm.log[0])
        steps.append({"step": sm.params.step, "exit_code": exit_code, "error": error,
                      "seconds": round(time.monotonic() - start, 3), "slurm_job_id": os.environ.get("SLURM_JOB_ID")})
    write_json(sm.output.status, {"format": STATUS_FORMAT, "version": STATUS_VERSION, "id": sm.wildcards.id,
                                  "folder": sm.params.folder, "steps": steps})


main(snakemake)  # noqa: F821 (given by Snakemake's script directive)
