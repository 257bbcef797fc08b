#!/usr/bin/env python3
"""The cohort workflow (workflow/Snakefile) on three small patients: two copies of the bundled CT at a coarse edge
length and a broken file.

  cohort_workflow_test.py local FACEHEX   two runs (the second does nothing), then a touched input reruns only its
                                          patient; the broken patient is reported failed, the others ok
  cohort_workflow_test.py slurm FACEHEX   the same three through the Slurm profile on a single-node Slurm started for
                                          the test (scripts/local-slurm.sh); exit code 77 (skipped) when Slurm cannot
                                          run here at all
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CT = os.path.join(REPO, "resources", "ct", "headsq")
LANDMARKS = os.path.join(REPO, "tests", "data", "landmarks", "headsq.json")
SKIP = 77
MODE, FACEHEX = sys.argv[1], sys.argv[2]
# The test's own cluster, on its own ports, so that a cluster started by hand keeps running.
SLURM_ENV = dict(os.environ, FACEHEX_SLURM_DIR=os.path.join(tempfile.gettempdir(), f"facehex-slurm-test-{os.getpid()}"),
                 FACEHEX_SLURMCTLD_PORT="16917", FACEHEX_SLURMD_PORT="16918")


class CohortWorkflow(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="facehex-cohort-")
        self.out = os.path.join(self.dir, "out")
        for pid in ("a", "b"):
            os.makedirs(os.path.join(self.dir, pid))
            for f in ("headsq.mhd", "headsq.raw"):
                shutil.copy(os.path.join(CT, f), os.path.join(self.dir, pid, f))
        with open(os.path.join(self.dir, "broken.vtu"), "w") as f:
            f.write("not a mesh\n")
        # At this edge length the profile's vertices are 5 mm apart, too few for the automatic landmarks: they are given.
        with open(os.path.join(self.dir, "manifest.csv"), "w") as f:
            f.write("id,input,landmarks,options\n"
                    f"a,a/headsq.mhd,{LANDMARKS},\n"
                    f"b,b/headsq.mhd,{LANDMARKS},--iterations 3\n"
                    "c,broken.vtu,,\n")

    def tearDown(self):
        shutil.rmtree(self.dir)

    def snakemake(self, *extra, env=None):
        command = ["snakemake", "--snakefile", os.path.join(REPO, "workflow", "Snakefile"), *extra, "--config",
                   f"manifest={self.dir}/manifest.csv", f"out={self.out}", f"facehex={FACEHEX}", "edge_length=5",
                   "threads=1"]
        r = subprocess.run(command, cwd=self.dir, capture_output=True, text=True, env=env)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        return r.stdout + r.stderr

    def cohort(self):
        with open(os.path.join(self.out, "cohort.json")) as f:
            return {p["id"]: p for p in json.load(f)["patients"]}

    def status(self, pid):
        with open(os.path.join(self.out, pid, "transfer.status.json")) as f:
            return json.load(f)

    def mtime(self, pid, name):
        return os.stat(os.path.join(self.out, pid, name)).st_mtime_ns

    def assert_report(self):
        """Two patients meshed, the broken one failed with facehex's error line naming its file."""
        patients = self.cohort()
        self.assertEqual(list(patients), ["a", "b", "c"])
        for pid in ("a", "b"):
            self.assertEqual(patients[pid]["status"], "ok", patients[pid])
            self.assertEqual(patients[pid]["cells"], 6342)
            self.assertEqual(patients[pid]["inverted"], 0)
            self.assertGreater(patients[pid]["tets"], 0)
            self.assertGreater(patients[pid]["landmarks_found"], 0)
            # where the standard's landmarks landed on the patient's, measured on every run with landmarks
            self.assertGreater(patients[pid]["landing_max_mm"], 0)
            self.assertLessEqual(patients[pid]["landing_mean_mm"], patients[pid]["landing_max_mm"])
        c = patients["c"]
        self.assertEqual((c["status"], c["failed_step"], c["exit_code"]), ("failed", "transfer", 1))
        self.assertTrue(c["error"].startswith("error: ") and "broken.vtu" in c["error"], c["error"])
        self.assertIsNone(c["cells"])
        with open(os.path.join(self.out, "cohort.csv")) as f:
            self.assertEqual(len(f.read().splitlines()), 4)
        for png in ("cohort_dihedral_change.png", "cohort_shape.png", "cohort_time.png"):
            with open(os.path.join(self.out, png), "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n", png)
        return patients

    @unittest.skipUnless(MODE == "local", "local runs")
    def test_resumes_and_reruns_only_a_changed_patient(self):
        self.snakemake("--cores", "2")
        patients = self.assert_report()
        self.assertEqual(patients["a"]["slurm_jobs"], [])
        self.assertEqual([s["step"] for s in self.status("a")["steps"]], ["segment", "transfer"])
        before = {pid: self.mtime(pid, "transfer.status.json") for pid in ("a", "b", "c")}
        report = self.mtime("b", "report.json")

        self.assertIn("Nothing to be done", self.snakemake("--cores", "2"))
        self.assertEqual(before, {pid: self.mtime(pid, "transfer.status.json") for pid in before})

        # A new data file under the same header: b alone is segmented and meshed again.
        os.utime(os.path.join(self.dir, "b", "headsq.raw"))
        self.snakemake("--cores", "2")
        after = {pid: self.mtime(pid, "transfer.status.json") for pid in before}
        self.assertEqual(after["a"], before["a"])
        self.assertEqual(after["c"], before["c"])
        self.assertGreater(after["b"], before["b"])
        self.assertGreater(self.mtime("b", "report.json"), report)
        self.assert_report()

    @unittest.skipUnless(MODE == "slurm", "Slurm runs")
    def test_runs_each_patient_as_one_slurm_job(self):
        start = subprocess.run([os.path.join(REPO, "scripts", "local-slurm.sh"), "start"], env=SLURM_ENV,
                               capture_output=True, text=True)
        if start.returncode == SKIP:
            print("skipped: " + start.stderr.strip())
            sys.exit(SKIP)
        self.assertEqual(start.returncode, 0, start.stderr)
        try:
            env = dict(os.environ, SLURM_CONF=os.path.join(SLURM_ENV["FACEHEX_SLURM_DIR"], "slurm.conf"))
            self.snakemake("--profile", os.path.join(REPO, "workflow", "profiles", "slurm"), "--jobs", "3",
                           "--set-resources", "segment:mem_mb=1000", "transfer:mem_mb=1000", env=env)
        finally:
            subprocess.run([os.path.join(REPO, "scripts", "local-slurm.sh"), "stop"], env=SLURM_ENV)
            shutil.rmtree(SLURM_ENV["FACEHEX_SLURM_DIR"], ignore_errors=True)
        patients = self.assert_report()
        jobs = {pid: patients[pid]["slurm_jobs"] for pid in patients}
        # Each patient ran in one Slurm job (both steps of a CT), each in its own.
        self.assertEqual([len(jobs[pid]) for pid in ("a", "b", "c")], [2, 2, 1], jobs)
        for pid in ("a", "b"):
            self.assertEqual(len(set(jobs[pid])), 1, jobs)
        self.assertEqual(len({j[0] for j in jobs.values()}), 3, jobs)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]])
