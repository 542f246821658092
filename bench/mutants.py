#!/usr/bin/env python3
"""Regenerates a corpus of corrupt characters from Debian's assimp test models (X, FBX, glTF, GLB, MD5 and
Collada) and runs skinned-decimate on every one. Each run must:

- end with exit 0, 1 or 2 (never a signal) within --timeout seconds (default 60);
- print at most --max-stderr bytes (default 4096) to stderr, every line printable UTF-8;
- when it fails, say why in exactly one error line;
- when it succeeds, write a file the Khronos glTF validator passes with 0 errors (--no-validate skips it).

  bench/mutants.py --cli build/apps/skinned-decimate --count 3000 --seed 1 --out bench/results/mutants

Deterministic: the same --seed gives the same mutants. Writes a summary (counts per seed file and outcome)
to OUT/summary.json and keeps every mutant that failed a rule in OUT/failures/.
"""
import argparse, base64, concurrent.futures as cf, json, os, random, re, shutil, struct, subprocess, sys, tempfile, time

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
    ("glTF2/simple_skin/simple_skin.gltf", "glb"),  # the skinned, animated glTF as a GLB (made here)
    ("Collada/box_nested_animation.dae", "text"),
    ("Collada/library_animation_clips.dae", "text"),
]
TOOLS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools")


def gltf_to_glb(text: bytes) -> bytes:
    """A .gltf whose buffers are data URIs, as one GLB with a single binary chunk."""
    doc = json.loads(text)
    blob = b""
    for b in doc["buffers"]:
        data = base64.b64decode(b.pop("uri").split(",", 1)[1])
        for v in doc["bufferViews"]:
            if v["buffer"] == doc["buffers"].index(b):
                v["byteOffset"] = v.get("byteOffset", 0) + len(blob)
        blob += data + b"\0" * (-len(data) % 4)
    for v in doc["bufferViews"]:
        v["buffer"] = 0
    doc["buffers"] = [{"byteLength": len(blob)}]
    js = json.dumps(doc).encode()
    js += b" " * (-len(js) % 4)
    total = 12 + 8 + len(js) + 8 + len(blob)
    return (struct.pack("<III", 0x46546C67, 2, total) + struct.pack("<II", len(js), 0x4E4F534A) + js +
            struct.pack("<II", len(blob), 0x004E4942) + blob)


NUMBER = re.compile(rb"-?\d+(\.\d+)?([eE][-+]?\d+)?")
REPLACEMENTS = [b"0", b"-1", b"1e30", b"-1e30", b"nan", b"inf", b"4294967295", b"2147483648", b"99999999", b"3"]


def mutate(data: bytes, kind: str, rng: random.Random) -> bytes:
    b = bytearray(data)
    op = rng.choice(["flip", "bytes", "delete", "duplicate", "truncate"] + (["number"] * 3 if kind != "binary" else []))
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
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds before a run counts as a hang")
    ap.add_argument("--max-stderr", type=int, default=4096, help="bytes of stderr a run may print")
    ap.add_argument("--no-validate", action="store_true", help="skip the glTF validator on successful runs")
    ap.add_argument("--out", default="bench/results/mutants")
    ap.add_argument("--extra-args", default="", help="passed to the CLI, e.g. --no-isolate")
    args = ap.parse_args()
    cli = os.path.abspath(args.cli)
    os.makedirs(os.path.join(args.out, "failures"), exist_ok=True)
    rng = random.Random(args.seed)
    seeds = []
    for p, k in SEEDS:
        data = open(os.path.join(MODELS, p), "rb").read()
        if k == "glb":
            data, p = gltf_to_glb(data), os.path.splitext(p)[0] + ".glb"
        seeds.append((os.path.join(MODELS, p), k, data))
    validator = None if args.no_validate else os.path.join(TOOLS, "validate-gltf.mjs")
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
    slowest = 0.0
    t0 = time.time()
    with cf.ThreadPoolExecutor(args.jobs) as ex:
        futs = {ex.submit(run_cli, cli, args.extra_args, m, work, args.timeout, args.max_stderr, validator): (i, m, src)
                for i, m, src in jobs}
        for n, fut in enumerate(cf.as_completed(futs)):
            i, m, src = futs[fut]
            outcome, code, msg, secs = fut.result()
            slowest = max(slowest, secs)
            s = summary.setdefault(src, {})
            s[outcome] = s.get(outcome, 0) + 1
            for kind in ("the reader crashed", "the reader ran out of memory", "the reader took longer"):
                if kind in msg:
                    caught[kind] = caught.get(kind, 0) + 1
            if outcome not in ("ok", "error"):
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
              "slowest_run_seconds": round(slowest, 1), "validated": validator is not None, "total": total, "isolated_reader_refusals": caught, "per_seed_file": summary, "failures": failures}
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(result, f, indent=2)
    print(json.dumps({"total": total, "isolated_reader_refusals": caught, "seconds": result["seconds"],
                      "slowest_run_seconds": result["slowest_run_seconds"]}))
    return 1 if failures else 0


PRINTABLE = re.compile(r"[^\x00-\x1f\x7f\x80-\x9f]*")


def run_cli(cli, extra, path, workdir, timeout, max_stderr, validator):
    """One run: its outcome (ok, error, crash, hang, flood, bad-message, invalid-output), exit code, its error
    line (or what went wrong) and seconds."""
    out = os.path.join(workdir, os.path.basename(path) + ".glb")
    cmd = [cli, path, "-o", out, "--ratio", "0.5", "--poses", "2", "--quiet", "--time-limit", "30",
           "--max-memory", "4096"] + extra.split()
    t0 = time.time()
    with tempfile.TemporaryFile() as err_file:  # a file, not a pipe: a flood must not fill this process
        try:
            p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=err_file, timeout=timeout)
            code = p.returncode
        except subprocess.TimeoutExpired:
            code = "hang"
        secs = time.time() - t0
        size = err_file.tell()
        err_file.seek(0)
        raw = err_file.read(max_stderr + 1)
    try:
        err = raw.decode("utf-8")
        printable = all(PRINTABLE.fullmatch(line) for line in err.splitlines())
    except UnicodeDecodeError:
        err, printable = raw.decode("utf-8", "replace"), False
    errors = [l for l in err.splitlines() if l.startswith("skinned-decimate:") and ": warning: " not in l]
    msg = errors[-1] if errors else ""
    if code == "hang":
        outcome = "hang"
    elif code not in (0, 1, 2):
        outcome = "crash"
    elif size > max_stderr:
        outcome, msg = "flood", f"{size} bytes of stderr"
    elif not printable or (code != 0 and (len(errors) != 1 or len(err.splitlines()) != 1 + err.count(": warning: "))):
        outcome = "bad-message"
    elif code == 0 and validator and os.path.exists(out):
        v = subprocess.run(["node", validator, out], capture_output=True, text=True)
        outcome = "ok" if v.returncode == 0 else "invalid-output"
        if v.returncode != 0:
            msg = " | ".join(l.strip() for l in v.stdout.splitlines()[1:6])
    else:
        outcome = "ok" if code == 0 else "error"
    if os.path.exists(out):
        os.remove(out)
    return outcome, code, msg, secs


if __name__ == "__main__":
    sys.exit(main())
