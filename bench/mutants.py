#!/usr/bin/env python3
"""Regenerates a corpus of corrupt characters from Debian's assimp test models and runs skinned-decimate
on every one. The CLI must end each run with exit 0, 1 or 2 (never a signal, never a hang) and, when it
fails, say why in one line.

  bench/mutants.py --cli build/apps/skinned-decimate --count 3000 --seed 1 --out bench/results/mutants

Deterministic: the same --seed gives the same mutants. Writes a summary (counts per format and outcome)
to OUT/summary.json and keeps every mutant that crashed or hung in OUT/failures/.
"""
import argparse, concurrent.futures as cf, json, os, random, re, shutil, subprocess, sys, tempfile, time

MODELS = "/usr/share/assimp/models"
SEEDS = [  # (path, kind) - the formats the importer is asked to read most, small enough to mutate fast
    ("X/Testwuson.X", "text"),
    ("X/test_cube_binary.x", "binary"),
    ("X/anim_test.x", "text"),
    ("MD5/SimpleCube.md5mesh", "text"),
    ("FBX/animation_with_skeleton.fbx", "binary"),
    ("FBX/huesitos.fbx", "binary"),
    ("glTF2/simple_skin/simple_skin.gltf", "text"),
    ("glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", "binary"),
]
NUMBER = re.compile(rb"-?\d+(\.\d+)?([eE][-+]?\d+)?")
REPLACEMENTS = [b"0", b"-1", b"1e30", b"-1e30", b"nan", b"inf", b"4294967295", b"2147483648", b"99999999", b"3"]


def mutate(data: bytes, kind: str, rng: random.Random) -> bytes:
    b = bytearray(data)
    op = rng.choice(["flip", "bytes", "delete", "duplicate", "truncate"] + (["number"] * 3 if kind == "text" else []))
    n = len(b)
    if op == "flip":
        for _ in range(rng.randint(1, 8)):
            i = rng.randrange(n)
            b[i] ^= 1 << rng.randrange(8)
    elif op == "bytes":
        for _ in range(rng.randint(1, 8)):
            b[rng.randrange(n)] = rng.choice([0, 0xFF, 0x7F, 0x80, rng.randrange(256)])
    elif op == "delete":
        i = rng.randrange(n)
        del b[i:i + rng.randint(1, max(1, n // 20))]
    elif op == "duplicate":
        i = rng.randrange(n)
        chunk = b[i:i + rng.randint(1, max(1, n // 20))]
        j = rng.randrange(n)
        b[j:j] = chunk
    elif op == "truncate":
        del b[rng.randint(1, max(1, n - 1)):]
    else:  # replace numbers in a text format
        matches = list(NUMBER.finditer(bytes(b)))
        for m in sorted(rng.sample(matches, min(len(matches), rng.randint(1, 4))), key=lambda m: -m.start()):
            b[m.start():m.end()] = rng.choice(REPLACEMENTS)
    return bytes(b)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", required=True)
    ap.add_argument("--count", type=int, default=3000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds before a run counts as a hang")
    ap.add_argument("--out", default="bench/results/mutants")
    ap.add_argument("--extra-args", default="", help="passed to the CLI, e.g. --no-isolate")
    args = ap.parse_args()
    cli = os.path.abspath(args.cli)
    os.makedirs(os.path.join(args.out, "failures"), exist_ok=True)
    rng = random.Random(args.seed)
    seeds = [(os.path.join(MODELS, p), k, open(os.path.join(MODELS, p), "rb").read()) for p, k in SEEDS]
    work = tempfile.mkdtemp(prefix="omsk-mutants-")
    jobs = []
    for i in range(args.count):
        path, kind, data = seeds[i % len(seeds)]
        ext = os.path.splitext(path)[1]
        m = os.path.join(work, f"m{i:05d}{ext}")
        with open(m, "wb") as f:
            f.write(mutate(data, kind, rng))
        # resources a text format refers to (simple_skin embeds its buffers; the X files their textures)
        jobs.append((i, m, os.path.relpath(path, MODELS)))
    summary = {}
    caught = {}  # refusals by the isolated reader, by kind
    failures = []
    t0 = time.time()
    with cf.ThreadPoolExecutor(args.jobs) as ex:
        futs = {ex.submit(run_cli, cli, args.extra_args, m, work, args.timeout): (i, m, src) for i, m, src in jobs}
        for n, fut in enumerate(cf.as_completed(futs)):
            i, m, src = futs[fut]
            outcome, code, msg, secs = fut.result()
            s = summary.setdefault(src, {})
            s[outcome] = s.get(outcome, 0) + 1
            for kind in ("the reader crashed", "the reader ran out of memory", "the reader took longer"):
                if kind in msg:
                    caught[kind] = caught.get(kind, 0) + 1
            if outcome in ("crash", "hang", "bad-message"):
                dst = os.path.join(args.out, "failures", os.path.basename(m))
                shutil.copy(m, dst)
                failures.append({"mutant": dst, "seed_file": src, "outcome": outcome, "exit": str(code), "message": msg})
            if (n + 1) % 250 == 0:
                print(f"{n + 1}/{len(jobs)} mutants, {len(failures)} failures, {time.time() - t0:.0f} s", flush=True)
    shutil.rmtree(work, ignore_errors=True)
    total = {}
    for s in summary.values():
        for k, v in s.items():
            total[k] = total.get(k, 0) + v
    result = {"count": args.count, "seed": args.seed, "cli_args": args.extra_args, "seconds": round(time.time() - t0, 1),
              "total": total, "isolated_reader_refusals": caught, "per_seed_file": summary, "failures": failures}
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(result, f, indent=2)
    print(json.dumps({"total": total, "isolated_reader_refusals": caught, "seconds": result["seconds"]}))
    return 1 if failures else 0


def run_cli(cli, extra, path, workdir, timeout):
    out = os.path.join(workdir, os.path.basename(path) + ".glb")
    cmd = [cli, path, "-o", out, "--ratio", "0.5", "--poses", "2", "--quiet", "--time-limit", "30",
           "--max-memory", "4096"] + extra.split()
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=timeout)
        code, err = p.returncode, p.stderr.decode("utf-8", "replace")
    except subprocess.TimeoutExpired:
        code, err = "hang", ""
    errors = [l for l in err.splitlines() if l.startswith("skinned-decimate:") and ": warning: " not in l]
    if code in (0, 1, 2):
        outcome = "ok" if code == 0 else "error"
        if code != 0 and len(errors) != 1:
            outcome = "bad-message"
    else:
        outcome = "hang" if code == "hang" else "crash"
    if os.path.exists(out):
        os.remove(out)
    return outcome, code, errors[-1] if errors else "", time.time() - t0


if __name__ == "__main__":
    sys.exit(main())
