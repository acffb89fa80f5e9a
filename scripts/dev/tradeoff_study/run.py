"""Running: `simulate` per configuration, two at a time, each run cached as JSON."""
import concurrent.futures
import csv
import json
import os
import re
import subprocess
import sys
import tempfile
import time

from .grid import ENERGY_TIME, PLOT_DT, SAMPLE_DT, THETA_WINDOW, WORKER_TIMEOUT, estimated_cost


def load_json(path):
    """simulate writes inf/nan as bare words when a run blew up: read them as numbers."""
    with open(path) as f:
        text = f.read()
    text = re.sub(r"(?<=[:\s])(-?)inf\b", r"\1Infinity", text)
    text = re.sub(r"(?<=[:\s])-?nan\b", "NaN", text)
    return json.loads(text)


def sample_csv(path, duration):
    """theta and energy on the common grid t = k*SAMPLE_DT (rows are written every step of the
    decimation, which is chosen so that they fall on it)."""
    theta = {}
    energy = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            k = round(float(row["t"]) / SAMPLE_DT)
            if abs(float(row["t"]) - k * SAMPLE_DT) > 1e-9:
                continue
            theta[k] = float(row["theta"])
            energy[k] = float(row["energy"])
    n_window = round(THETA_WINDOW / SAMPLE_DT)
    n_energy = round(ENERGY_TIME / SAMPLE_DT)
    stride = round(PLOT_DT / SAMPLE_DT)
    n_end = round(duration / SAMPLE_DT)
    return {
        "theta_window": [theta.get(k) for k in range(n_window + 1)],
        "energy_2": energy.get(n_energy),
        "theta_plot": [theta.get(k) for k in range(0, n_end + 1, stride)],
    }


def execute(simulate, config, out_dir):
    """Runs one configuration; returns the record stored in OUT/runs/<id>.json."""
    args = [simulate, "--quiet", "--friction-set", config["set"], "--solver", config["solver"],
            "--dt", repr(config["dt"]), "--duration", repr(config["duration"]),
            "--tolerance", repr(config["tolerance"]), "--gyroscopic", config["gyroscopic"],
            "--spin", repr(config["spin"])]
    if config["tolerance_abs"] is not None:
        args += ["--tolerance-abs", repr(config["tolerance_abs"])]
    if config["max_iterations"] is not None:
        args += ["--max-iterations", str(config["max_iterations"])]
    if config["unmapped"]:
        args.append("--unmapped-drilling-sets")
    with tempfile.TemporaryDirectory(dir=out_dir) as tmp:
        summary_path = os.path.join(tmp, "summary.json")
        args += ["--summary", summary_path]
        csv_path = os.path.join(tmp, "run.csv")
        if config["csv"]:
            decimate = max(1, round(SAMPLE_DT / config["dt"]))
            args += ["--csv", csv_path, "--decimate", str(decimate)]
        started = time.time()
        completed = subprocess.run(args, capture_output=True, text=True, timeout=WORKER_TIMEOUT)
        if completed.returncode != 0 and config["kind"] == "gyro" and "finite" in completed.stderr:
            # the explicit gyroscopic term blew the state up and the core refused the non-finite
            # contact problem: that is the datum of this sweep
            return {"config": config, "blown_up": completed.stderr.strip(),
                    "process_seconds": time.time() - started}
        if completed.returncode != 0:
            raise RuntimeError("%s failed (%d): %s" % (" ".join(args), completed.returncode,
                                                       completed.stderr.strip()))
        record = {"config": config, "summary": load_json(summary_path),
                  "process_seconds": time.time() - started}
        if config["csv"]:
            record.update(sample_csv(csv_path, config["duration"]))
    return record


def run_all(simulate, runs, out_dir, jobs, rerun):
    """Runs what is not cached yet, `jobs` processes at a time, longest first."""
    record_dir = os.path.join(out_dir, "runs")
    os.makedirs(record_dir, exist_ok=True)
    records = {}
    todo = []
    for config in runs:
        path = os.path.join(record_dir, config["id"] + ".json")
        if not rerun and os.path.exists(path):
            record = load_json(path)
            if record.get("config") == config:
                records[config["id"]] = record
                continue
        todo.append(config)
    todo.sort(key=estimated_cost, reverse=True)
    print("tradeoff: %d runs cached, %d to run (%d at a time)" % (len(records), len(todo), jobs),
          file=sys.stderr)
    started = time.time()
    failures = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(execute, simulate, c, out_dir): c for c in todo}
        for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
            config = futures[future]
            try:
                record = future.result()
            except (RuntimeError, subprocess.TimeoutExpired) as error:
                failures.append(str(error))
                print("tradeoff: %s" % error, file=sys.stderr)
                continue
            with open(os.path.join(record_dir, config["id"] + ".json"), "w") as f:
                json.dump(record, f)
            records[config["id"]] = record
            print("tradeoff: [%d/%d] %.0f s  %s (%.2f s)" % (done, len(todo), time.time() - started,
                                                           config["id"], record["process_seconds"]),
                  file=sys.stderr)
    return records, failures, time.time() - started
