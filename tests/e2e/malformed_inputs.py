#!/usr/bin/env python3
"""Malformed-input cases for every tool (issue 19; docs/cli.md "Conditions and exit codes").

Each case runs one tool on one bad input (a damaged file, a bad config file, a bad option
value, an impossible output path) and asserts:
  - the exit code of docs/cli.md's table (2 usage/config, 3 bad input data, 4 I/O),
  - that the one-line message names the file (for a file) and the field or key at fault,
  - that the tool's output folder, holding the outputs of an earlier good run, is unchanged
    (byte for byte) and holds no temporary file.
Usage: malformed_inputs.py BIN_DIR WORK_DIR  (exit 0 when every case holds, 1 otherwise).
"""
import hashlib
import json
import os
import shutil
import subprocess
import sys

BIN, WORK = sys.argv[1], sys.argv[2]
os.makedirs(WORK, exist_ok=True)
os.chdir(WORK)
BAD = "bad"  # damaged inputs are written here
os.makedirs(BAD, exist_ok=True)
failures = []
cases = 0


def tool(name):
    return os.path.join(BIN, name)


def run(cmd, timeout=300):
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=timeout)
    return p.returncode, p.stderr.decode(errors="replace")


def must(cmd):
    rc, err = run(cmd, timeout=900)
    if rc != 0:
        sys.exit(f"set-up failed ({rc}): {' '.join(cmd)}\n{err}")


def snapshot(folder):
    out = {}
    for root, _, files in os.walk(folder):
        for f in files:
            if f == ".mapfuse.lock":
                continue
            p = os.path.join(root, f)
            with open(p, "rb") as fh:
                out[os.path.relpath(p, folder)] = hashlib.sha1(fh.read()).hexdigest()
    return out


def case(name, cmd, code, names=(), out=None):
    """Runs one case. `names`: substrings the message must hold (file, field or key)."""
    global cases
    cases += 1
    before = snapshot(out) if out else None
    try:
        rc, err = run(cmd, timeout=120)
    except subprocess.TimeoutExpired:
        failures.append(f"{name}: hung (> 120 s)")
        return
    problems = []
    if rc != code:
        problems.append(f"exit {rc}, expected {code}")
    for n in names:  # a list: any one of its strings
        alternatives = n if isinstance(n, list) else [n]
        if not any(a in err for a in alternatives):
            problems.append(f"message does not name '{alternatives[0]}'")
    if out:
        after = snapshot(out)
        if after != before:
            problems.append("earlier outputs changed")
        if any(".tmp-" in f for f in after):
            problems.append("temporary files left")
    if problems:
        last = err.strip().splitlines()[-1] if err.strip() else "(no message)"
        failures.append(f"{name}: {'; '.join(problems)} -- stderr: {last[:300]}")


def write(name, data):
    path = os.path.join(BAD, name)
    with open(path, "wb" if isinstance(data, bytes) else "w") as fh:
        fh.write(data)
    return path


# ---------------------------------------------------------------- good inputs and outputs
must([tool("simulate"), "-q", "--traversals", "3", "--route-length", "400", "-o", "sim"])
lsms = sorted(os.path.join("sim/lsm", f) for f in os.listdir("sim/lsm"))
must([tool("georef"), "-q", "-o", "geo"] + lsms)
geo = sorted(os.path.join("geo", f) for f in os.listdir("geo") if f.endswith(".cbor"))
must([tool("align"), "-q", "-o", "al"] + geo)
al = sorted(os.path.join("al", f) for f in os.listdir("al") if f.endswith(".cbor"))
must([tool("aggregate"), "-q", "-o", "agg"] + al)
must([tool("tile"), "-q", "-o", "tiles"] + geo)
truth = "sim/truth/vector_map.json"
must([tool("evaluate"), "map", "-q", "--map", "agg/map.cbor", "--truth", truth, "-o", "ev"])
must([tool("simulate"), "-q", "--level", "frames", "--traversals", "1", "--route-length", "200",
      "-o", "simf"])
frames = os.path.join("simf/frames", sorted(os.listdir("simf/frames"))[0])
must([tool("lsm-build"), "-q", "-o", "lsmb", frames])
rc = subprocess.run([tool("simulate-lidar"), "-q", "--frames", "4", "-o", "simlidar"],
                    stdout=subprocess.PIPE, check=True)
drive = rc.stdout.decode().strip().splitlines()[-1]
must([tool("lidar-semantic-map"), "-q", drive, "-o", "lmap"])
must([tool("evaluate"), "voxels", "-q", "--drive", drive, "--map", "lmap/map.ply", "-o", "evv"])

# The tools with the command of a good run, the folder it writes and the config stage name.
TOOLS = {
    "georef": ([tool("georef"), "-o", "geo"] + lsms, "geo", "georef"),
    "align": ([tool("align"), "-o", "al"] + geo, "al", "align"),
    "tile": ([tool("tile"), "-o", "tiles"] + geo, "tiles", "tile"),
    "aggregate": ([tool("aggregate"), "-o", "agg"] + al, "agg", "aggregate"),
    "evaluate map": ([tool("evaluate"), "map", "--map", "agg/map.cbor", "--truth", truth, "-o",
                      "ev"], "ev", "evaluate"),
    "lsm-build": ([tool("lsm-build"), "-o", "lsmb", frames], "lsmb", "lsm-build"),
    "lidar-semantic-map": ([tool("lidar-semantic-map"), drive, "-o", "lmap"], "lmap",
                           "lidar-semantic-map"),
    "evaluate voxels": ([tool("evaluate"), "voxels", "--drive", drive, "--map", "lmap/map.ply",
                         "-o", "evv"], "evv", "evaluate-voxels"),
    "simulate": ([tool("simulate"), "--traversals", "1", "--route-length", "200", "-o", "sim2"],
                 None, "simulate"),
    "simulate-lidar": ([tool("simulate-lidar"), "--frames", "2", "-o", "simlidar2"], None,
                       "simulate-lidar"),
}

# ---------------------------------------------------------------- configuration files (exit 2)
CONFIG_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "configs")


def first_number_key(stage):
    with open(os.path.join(CONFIG_DIR, stage + ".json")) as fh:
        cfg = json.load(fh)
    ints = [k for k, v in cfg.items() if isinstance(v, int) and not isinstance(v, bool)]
    nums = [k for k, v in cfg.items() if isinstance(v, float)]
    return cfg, (ints[0] if ints else None), (nums[0] if nums else None)


for label, (cmd, out, stage) in TOOLS.items():
    cfg, int_key, num_key = first_number_key(stage)
    any_key = next(iter(cfg))
    tag = label.replace(" ", "_")
    bad_configs = [
        ("empty config", "", ()),
        ("truncated config", json.dumps(cfg)[:-7], ()),
        ("config not an object", "[1, 2]", ()),
        ("unknown key", json.dumps({"no_such_key": 1}), ("no_such_key",)),
        ("null value", json.dumps({any_key: None}), (any_key,)),
        ("text for a number", json.dumps({(num_key or int_key): "many"}), (num_key or int_key,)),
    ]
    if num_key:
        bad_configs += [("NaN", '{"%s": NaN}' % num_key, ()),
                        ("huge number", json.dumps({num_key: 1e308}), (num_key,)),
                        ("negative huge", json.dumps({num_key: -1e308}), (num_key,))]
    if int_key:
        bad_configs += [("integer past 32 bits", '{"%s": 4294967297}' % int_key, (int_key,)),
                        ("integer past 64 bits", '{"%s": 99999999999999999999}' % int_key,
                         (int_key,)),
                        ("fraction for an integer", json.dumps({int_key: 2.5}), (int_key,))]
    for what, text, keys in bad_configs:
        path = write(f"{tag}-{what.replace(' ', '_')}.json", text)
        case(f"{label}: {what}", cmd[:1] + cmd[1:2] * (cmd[1] in ("map", "voxels")) +
             ["--config", path] + cmd[1 + (cmd[1] in ("map", "voxels")):], 2,
             (os.path.basename(path),) + keys, out)
    # an option value that is not finite or out of range, from the command line
    if num_key:
        for value in ("nan", "inf", "-1e308"):
            opt = "--" + num_key.replace("_", "-")
            sub = cmd[1:2] if cmd[1] in ("map", "voxels") else []
            rest = cmd[1 + len(sub):]
            case(f"{label}: {opt} {value}", cmd[:1] + sub + [opt, value] + rest, 2,
                 ([num_key, opt],), out)
    if int_key:
        opt = "--" + int_key.replace("_", "-")
        sub = cmd[1:2] if cmd[1] in ("map", "voxels") else []
        case(f"{label}: {opt} 4294967297", cmd[:1] + sub + [opt, "4294967297"] + cmd[1 + len(sub):],
             2, ([int_key, opt],), out)
    # unknown option
    case(f"{label}: unknown option", cmd + ["--no-such-option"], 2, ("no-such-option",), out)
    # an output folder below a regular file: refused before any work (exit 4)
    with open(os.path.join(BAD, "a_file"), "w") as fh:
        fh.write("x")
    o = cmd.index("-o")
    case(f"{label}: output below a regular file",
         cmd[:o + 1] + [os.path.join(BAD, "a_file", "out")] + cmd[o + 2:], 4, ("a_file",))

# ---------------------------------------------------------------- LSM files (exit 3 / 2 / 4)
with open(geo[0], "rb") as fh:
    good_cbor = fh.read()
subprocess.run([tool("info"), geo[0]], stdout=subprocess.DEVNULL, check=True)
# a JSON LSM (georeferenced) to damage field by field
must([tool("simulate"), "-q", "--format", "json", "--traversals", "1", "--route-length", "200",
      "-o", "simj"])
simj = sorted(os.path.join("simj/lsm", f) for f in os.listdir("simj/lsm"))
must([tool("georef"), "-q", "-o", "geoj"] + simj)
json_lsm = sorted(os.path.join("geoj", f) for f in os.listdir("geoj") if f.endswith(".json")
                  and not f.startswith("georef."))[0]
with open(json_lsm) as fh:
    base = json.load(fh)


def damaged_copy(good, file_name, mutate):
    """Writes a deep copy of the JSON document `good`, changed by `mutate`, as BAD/file_name."""
    doc = json.loads(json.dumps(good))
    mutate(doc)
    return write(file_name, json.dumps(doc))


def damaged(name, mutate):
    return damaged_copy(base, name + ".lsm.json", mutate)


def set_path(doc, path, value):
    cur = doc
    for p in path[:-1]:
        cur = cur[p]
    cur[path[-1]] = value


lsm_cases = [
    ("empty file", write("empty.lsm.cbor", b""), 3, ()),
    ("truncated CBOR", write("trunc.lsm.cbor", good_cbor[: len(good_cbor) // 2]), 3, ()),
    ("CBOR of nested arrays", write("deep.lsm.cbor", b"\x81" * 200000), 3, ()),
    ("JSON of nested arrays", write("deep.lsm.json", "[" * 200000 + "]" * 200000), 3, ()),
    ("not JSON", write("text.lsm.json", "hello"), 3, ()),
    ("missing file", os.path.join(BAD, "missing.lsm.cbor"), 4, ()),
    ("a folder for a file", BAD, 4, ()),
]
if True:
    kf = base["keyframes"][0]
    pose_key = next(k for k in kf if "T_" in k or "pose" in k)
    lsm_cases += [
        ("wrong format tag", damaged("fmt", lambda d: d.update({"format": "other"})), 3,
         ("format",)),
        ("future version", damaged("ver", lambda d: d.update({"version": 99})), 3,
         ("version",)),
        ("no keyframes field", damaged("nokf", lambda d: d.pop("keyframes")), 3,
         ("keyframes",)),
        ("keyframe at 1e308", damaged("far", lambda d: d["keyframes"][0]["pose"].update(
            {"t": [1e308, 0.0, 0.0]})), 3, ("keyframes",)),
        ("keyframe rotation not unit", damaged("quat", lambda d: d["keyframes"][0]["pose"].update(
            {"q": [0.0, 0.0, 0.0, 0.0]})), 3, ("keyframes",)),
        ("text for a keyframe", damaged("kftext", lambda d: d["keyframes"].__setitem__(0, "x")), 3,
         ("keyframes",)),
        ("element anchored to no keyframe", damaged("anchor", lambda d: d["elements"][0].update(
            {"anchor": 987654321})), 3, ("anchor",)),
        ("element of unknown class", damaged("ecls", lambda d: d["elements"][0].update(
            {"class": "unicorn"})), 3, ("class",)),
        ("GPS fix at latitude 200", damaged("gps", lambda d: d["gps"][0].update({"lat": 200.0})
                                             if d["gps"] and isinstance(d["gps"][0], dict)
                                             else d.update({"gps": "x"})), 3, ("gps",)),
        ("keyframe stamps going back", damaged("stamp", lambda d: d["keyframes"][1].update(
            {"stamp": -5.0})), 3, ("keyframes",)),
        ("drive id a number", damaged("drv", lambda d: d.update({"drive_id": 5})), 3,
         ("drive_id",)),
    ]
for what, path, code, fields in lsm_cases:
    for label in ("georef", "align", "tile", "aggregate"):
        cmd, out, _ = TOOLS[label]
        ins = [a for a in cmd[1:] if a.endswith((".cbor", ".json"))]
        keep = [a for a in cmd if a not in ins]
        name = os.path.basename(path.rstrip("/"))
        case(f"{label}: LSM {what}", keep + [path] + ins[1:], code, (name,) + fields, out)
    case(f"info: LSM {what}", [tool("info"), path], code, (os.path.basename(path.rstrip('/')),))

# duplicate inputs (exit 2, both named)
shutil.copy(geo[0], os.path.join(BAD, "copy.lsm.cbor"))
for label in ("georef", "align", "tile", "aggregate"):
    cmd, out, _ = TOOLS[label]
    ins = [a for a in cmd[1:] if a.endswith((".cbor", ".json"))]
    keep = [a for a in cmd if a not in ins]
    case(f"{label}: same file twice", keep + ins + [ins[0]], 2, (os.path.basename(ins[0]),), out)
    src = geo[0] if label in ("tile",) else ins[0]
    shutil.copy(ins[0], os.path.join(BAD, "copy2.lsm.cbor"))
    case(f"{label}: one drive under two names", keep + ins + [os.path.join(BAD, "copy2.lsm.cbor")],
         2, ("copy2.lsm.cbor",), out)

# ---------------------------------------------------------------- vector maps (evaluate, info)
with open(truth) as fh:
    truth_doc = json.load(fh)


def damaged_map(name, mutate):
    return damaged_copy(truth_doc, name + ".map.json", mutate)


def first_point_list(doc):
    for inst in doc.get("instances", []):
        for k, v in inst.items():
            if isinstance(v, list) and v and isinstance(v[0], list):
                return v
    return None


map_cases = [
    ("empty map file", write("empty.map.json", ""), 3, ()),
    ("map not JSON", write("text.map.json", "{"), 3, ()),
    ("map of nested arrays", write("deep.map.json", "[" * 100000), 3, ()),
    ("map wrong format", damaged_map("mfmt", lambda d: d.update({"format": "x"})), 3,
     ("format",)),
    ("map future version", damaged_map("mver", lambda d: d.update({"version": 99})), 3,
     ("version",)),
    ("map instances not a list", damaged_map("minst", lambda d: d.update({"instances": 3})), 3,
     ("instances",)),
    ("map unknown class", damaged_map("mcls", lambda d: d["instances"][0].update(
        {"class": "unicorn"})), 3, ("class",)),
    ("map point at 1e308", damaged_map("mfar", lambda d: first_point_list(d)[0].__setitem__(
        0, 1e308)), 3, ()),
    ("map missing", os.path.join(BAD, "none.map.json"), 4, ()),
]
for what, path, code, fields in map_cases:
    name = os.path.basename(path)
    case(f"evaluate map: --map {what}", [tool("evaluate"), "map", "--map", path, "--truth", truth,
                                         "-o", "ev"], code, (name,) + fields, "ev")
    case(f"evaluate map: --truth {what}", [tool("evaluate"), "map", "--map", "agg/map.cbor",
                                           "--truth", path, "-o", "ev"], code, (name,) + fields,
         "ev")
    case(f"info: {what}", [tool("info"), path], code, (name,))

# ---------------------------------------------------------------- KITTI drives (lidar tools)
def copy_drive(name):
    dst = os.path.join(BAD, name, os.path.basename(os.path.dirname(drive)),
                       os.path.basename(drive))
    if os.path.exists(os.path.join(BAD, name)):
        shutil.rmtree(os.path.join(BAD, name))
    shutil.copytree(os.path.dirname(drive), os.path.dirname(dst))
    return dst


def first_file(folder):
    return os.path.join(folder, sorted(os.listdir(folder))[0])


drive_cases = []
d = copy_drive("velo_odd")
v = first_file(os.path.join(d, "velodyne_points", "data"))
with open(v, "ab") as fh:
    fh.write(b"\x01\x02\x03")
drive_cases.append(("velodyne size not a multiple of 16", d, 3, (os.path.basename(v),)))
d = copy_drive("velo_nan")
v = first_file(os.path.join(d, "velodyne_points", "data"))
with open(v, "r+b") as fh:
    fh.write(b"\x00\x00\xc0\x7f")  # a NaN x
drive_cases.append(("velodyne NaN coordinate", d, 3, (os.path.basename(v),)))
d = copy_drive("oxts_bad")
o = first_file(os.path.join(d, "oxts", "data"))
with open(o, "w") as fh:
    fh.write("49.0 8.0 abc\n")
drive_cases.append(("OXTS line not numbers", d, 3, (os.path.basename(o),)))
d = copy_drive("ts_bad")
t = os.path.join(d, "velodyne_points", "timestamps.txt")
with open(t, "w") as fh:
    fh.write("yesterday\n" * 50)
drive_cases.append(("timestamps malformed", d, 3, ("timestamps.txt",)))
date_dir = os.path.dirname(drive)
for calib in ("calib_cam_to_cam.txt", "calib_velo_to_cam.txt"):
    d = copy_drive("calib_" + calib[:9])
    c = os.path.join(os.path.dirname(d), calib)
    with open(c, "w") as fh:
        fh.write("R: 1 2\n")
    drive_cases.append((f"{calib} malformed", d, 3, (calib,)))
    d = copy_drive("calibx_" + calib[:9])
    os.remove(os.path.join(os.path.dirname(d), calib))
    drive_cases.append((f"{calib} missing", d, 4, (calib,)))
d = copy_drive("sem_bad")
sem = first_file(os.path.join(d, "semantics_02"))
shutil.copy(os.path.join(BAD, "a_file"), sem)
drive_cases.append(("semantics_02 frame not readable", d, 3, (os.path.basename(sem),)))
d = copy_drive("no_velo")
shutil.rmtree(os.path.join(d, "velodyne_points"))
drive_cases.append(("no velodyne folder", d, 4, ("velodyne",)))
for what, d, code, names in drive_cases:
    case(f"lidar-semantic-map: {what}", [tool("lidar-semantic-map"), d, "-o", "lmap"], code, names,
         "lmap")
case("lidar-semantic-map: --poses-file missing",
     [tool("lidar-semantic-map"), drive, "--pose-source", "poses_file", "--poses-file",
      os.path.join(BAD, "nope.txt"), "-o", "lmap"], 4, ("nope.txt",), "lmap")
write("poses_short.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n")
case("lidar-semantic-map: poses file shorter than the drive",
     [tool("lidar-semantic-map"), drive, "--pose-source", "poses_file", "--poses-file",
      os.path.join(BAD, "poses_short.txt"), "-o", "lmap"], 3, ("poses_short.txt",), "lmap")
write("poses_rot.txt", "2 0 0 0 0 1 0 0 0 0 1 0\n" * 10)
case("lidar-semantic-map: poses file with a non-rotation",
     [tool("lidar-semantic-map"), drive, "--pose-source", "poses_file", "--poses-file",
      os.path.join(BAD, "poses_rot.txt"), "-o", "lmap"], 3, ("poses_rot.txt", "line 1"), "lmap")
write("map_bad.ply", "ply\nformat ascii 1.0\nend_header\n")
case("evaluate voxels: map PLY not binary", [tool("evaluate"), "voxels", "--drive", drive,
                                             "--map", os.path.join(BAD, "map_bad.ply"), "-o", "evv"],
     3, ("map_bad.ply",), "evv")
write("map_trunc.ply", open("lmap/map.ply", "rb").read()[:2000])
case("evaluate voxels: map PLY truncated", [tool("evaluate"), "voxels", "--drive", drive,
                                            "--map", os.path.join(BAD, "map_trunc.ply"), "-o",
                                            "evv"], 3, ("map_trunc.ply",), "evv")

# ---------------------------------------------------------------- raw frames (lsm-build)
def copy_frames(name):
    dst = os.path.join(BAD, name)
    if os.path.exists(dst):
        shutil.rmtree(dst)
    shutil.copytree(frames, dst)
    return dst


d = copy_frames("frames_nojson")
os.remove(os.path.join(d, "frames.json"))
case("lsm-build: no frames.json", [tool("lsm-build"), "-o", "lsmb", d], 3, ("frames.json",), "lsmb")
d = copy_frames("frames_trunc")
fj = os.path.join(d, "frames.json")
text = open(fj).read()
open(fj, "w").write(text[: len(text) // 2])
case("lsm-build: frames.json truncated", [tool("lsm-build"), "-o", "lsmb", d], 3, ("frames.json",),
     "lsmb")
d = copy_frames("frames_deep")
open(os.path.join(d, "frames.json"), "w").write("[" * 100000)
case("lsm-build: frames.json nested arrays", [tool("lsm-build"), "-o", "lsmb", d], 3,
     ("frames.json",), "lsmb")
case("lsm-build: --poses missing file", [tool("lsm-build"), "--poses",
                                         os.path.join(BAD, "nope.txt"), "-o", "lsmb", frames], 4,
     ("nope.txt",), "lsmb")
case("lsm-build: frames folder missing", [tool("lsm-build"), "-o", "lsmb",
                                          os.path.join(BAD, "no_frames")], 4, ("no_frames",),
     "lsmb")

# ---------------------------------------------------------------- tiles.json (balance, stitch)
tj = json.load(open("tiles/tiles.json"))
for what, doc, fields in [
    ("tiles.json not JSON", "{", ()),
    ("tiles.json wrong format", json.dumps(dict(tj, format="x")), ("format",)),
    ("tiles.json tile size 0", json.dumps(dict(tj, tile_size=0)), ("tile_size",)),
    ("tiles.json tile size 1e308", json.dumps(dict(tj, tile_size=1e308)), ("tile_size",)),
    ("tiles.json two tiles one name", json.dumps(dict(tj, tiles=tj["tiles"] + tj["tiles"][:1])),
     ("tiles",)),
]:
    os.makedirs(os.path.join(BAD, "t_" + str(cases)), exist_ok=True)
    path = os.path.join(BAD, "t_" + str(cases), "tiles.json")
    open(path, "w").write(doc)
    case(f"balance: {what}", [tool("balance"), "--tiles", path, "-o", os.path.join(BAD, "bal")], 3,
         ("tiles.json",) + fields)
    case(f"stitch: {what}", [tool("stitch"), "--tiles", path, "-o",
                             os.path.join(BAD, "st", "map.cbor"), "agg/map.cbor"], 3,
         ("tiles.json",) + fields)

print(f"malformed_inputs: {cases} cases, {len(failures)} failed")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
