#!/usr/bin/env python3
"""Snakemake's cluster-status command for the Slurm profile: prints running, success or failed for the job id that
`sbatch --parsable` printed (JOBID or JOBID;CLUSTER), from scontrol, else from sacct where accounting is kept."""
import subprocess
import sys

RUNNING = {"PENDING", "CONFIGURING", "RUNNING", "COMPLETING", "SUSPENDED", "REQUEUED", "RESIZING", "STAGE_OUT"}


def state(job):
    try:
        out = subprocess.run(["scontrol", "show", "job", job], capture_output=True, text=True).stdout
        for field in out.split():
            if field.startswith("JobState="):
                return field.split("=", 1)[1]
        out = subprocess.run(["sacct", "-n", "-X", "-P", "-o", "State", "-j", job], capture_output=True,
                             text=True).stdout
        return out.split()[0].rstrip("+") if out.split() else "UNKNOWN"
    except OSError:
        return "UNKNOWN"


job_state = state(sys.argv[1].split(";")[0])
# Unknown (the controller is briefly unreachable): still running; Snakemake asks again.
print("success" if job_state == "COMPLETED" else "running" if job_state in RUNNING | {"UNKNOWN"} else "failed")
