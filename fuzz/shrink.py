#!/usr/bin/env python3
"""Cuts tool outputs to small seeds that are still valid inputs (fuzz/make-corpus.sh).

  shrink.py lsm-json FILE N          first N keyframes, N of their elements (8 points at most),
                                     GPS fixes in their time
  shrink.py vector-map-json FILE N   first N instances (20 points, 3 Bezier segments at most)
  shrink.py drive-frames DIR N       a raw drive folder's files, first N frames, "====" between
  shrink.py prob FILE W H            the top-left W x H pixels of a .prob image
  shrink.py ply FILE N / pcd FILE N  the first N points of a binary PLY / PCD
  shrink.py osm FILE N               N lanelets with their ways, nodes and regulatory elements
  shrink.py xodr FILE J N            OpenDRIVE: the J-th smallest junction with its roads (N at
                                     most; J = -1: the first N roads), links to removed roads and
                                     junctions dropped, numbers to 9 digits, no lateral profiles
Writes the seed to stdout.
"""
import json
import os
import sys
import xml.etree.ElementTree as ET

out = sys.stdout.buffer


def lsm_json(path, n):
    d = json.load(open(path))
    d["keyframes"] = d["keyframes"][:n]
    ids = {k["id"] for k in d["keyframes"]}
    d["elements"] = [e for e in d["elements"] if e["anchor"] in ids][:n]
    for e in d["elements"]:  # at most 8 points, with their covariances
        for key in ("points", "cov", "sigma"):
            if key in e:
                e[key] = e[key][:8]
    if d["keyframes"]:
        last = d["keyframes"][-1]["stamp"]
        d["gps"] = [g for g in d.get("gps", []) if g["stamp"] <= last][:n]
    out.write(json.dumps(d).encode())


def vector_map_json(path, n):
    d = json.load(open(path))
    d["instances"] = d["instances"][:n]
    for i in d["instances"]:  # long lane lines: 20 points, 3 Bezier segments at most
        if len(i.get("points", [])) > 20:
            i["points"] = i["points"][:20]
        if "bezier" in i:
            i["bezier"] = i["bezier"][:3]
    out.write(json.dumps(d).encode())


def drive_frames(folder, n):
    manifest = json.load(open(os.path.join(folder, "frames.json")))
    manifest["frame_count"] = n
    names = ["calibration", "imu", "wheel", "gps", "frames", "observations", "truth_poses"]
    for k in names:  # the fuzz target writes the parts under these fixed names
        manifest[k] = {"calibration": "calibration.json", "imu": "imu.csv", "wheel": "wheel.csv",
                       "gps": "gps.csv", "frames": "frames.csv",
                       "observations": "observations.jsonl",
                       "truth_poses": "truth_poses.csv"}[k]
    frames = open(os.path.join(folder, "frames.csv")).read().splitlines()[: n + 1]
    last = float(frames[-1].split(",")[1])

    def until(name, lines_max):  # header + rows up to the last frame's stamp
        rows = open(os.path.join(folder, name)).read().splitlines()
        keep = [rows[0]] + [r for r in rows[1:] if float(r.split(",")[0]) <= last + 0.5]
        return "\n".join(keep[: lines_max + 1]) + "\n"

    def first(name, count):
        p = os.path.join(folder, name)
        return "\n".join(open(p).read().splitlines()[:count]) + "\n" if os.path.exists(p) else ""

    parts = [json.dumps(manifest) + "\n", open(os.path.join(folder, "calibration.json")).read(),
             until("imu.csv", 60), until("wheel.csv", 30), until("gps.csv", 5),
             "\n".join(r.split(",")[0] + "," + r.split(",")[1] + "," for r in frames) + "\n",
             first("observations.jsonl", n), first("truth_poses.csv", n + 1)]
    out.write("====\n".join(p if p.endswith("\n") else p + "\n" for p in parts).encode())


def prob(path, w, h):
    data = open(path, "rb").read()
    eol = data.index(b"\n")
    _, _, width, height, channels = data[:eol].split()
    width, height, channels = int(width), int(height), int(channels)
    body = data[eol + 1:]
    rows = [body[(y * width) * channels:(y * width + w) * channels] for y in range(h)]
    out.write(b"mapfuse-prob 1 %d %d %d\n" % (w, h, channels) + b"".join(rows))


def cloud(path, n, kind):
    data = open(path, "rb").read()
    if kind == "ply":
        end = data.index(b"end_header\n") + len(b"end_header\n")
        header = data[:end].decode()
        total = int(next(l.split()[2] for l in header.splitlines() if l.startswith("element vertex")))
        stride = (len(data) - end) // max(total, 1)
        header = header.replace("element vertex %d" % total, "element vertex %d" % min(n, total))
    else:
        end = data.index(b"DATA binary\n") + len(b"DATA binary\n")
        header = data[:end].decode()
        total = int(next(l.split()[1] for l in header.splitlines() if l.startswith("POINTS")))
        stride = (len(data) - end) // max(total, 1)
        header = header.replace("WIDTH %d" % total, "WIDTH %d" % min(n, total))
        header = header.replace("POINTS %d" % total, "POINTS %d" % min(n, total))
    out.write(header.encode() + data[end:end + min(n, total) * stride])


def osm(path, n):
    root = ET.parse(path).getroot()
    nodes = {e.get("id"): e for e in root.findall("node")}
    ways = {e.get("id"): e for e in root.findall("way")}
    relations = root.findall("relation")
    lanelets = [r for r in relations
                if any(t.get("k") == "type" and t.get("v") == "lanelet" for t in r.findall("tag"))][:n]
    keep_rel = list(lanelets)
    reg_ids = {m.get("ref") for r in lanelets for m in r.findall("member")
               if m.get("role") == "regulatory_element"}
    keep_rel += [r for r in relations if r.get("id") in reg_ids]
    way_ids = {m.get("ref") for r in keep_rel for m in r.findall("member") if m.get("type") == "way"}
    keep_ways = [ways[w] for w in way_ids if w in ways]
    node_ids = {nd.get("ref") for w in keep_ways for nd in w.findall("nd")}
    new = ET.Element("osm", root.attrib)
    for i in node_ids:
        if i in nodes:
            new.append(nodes[i])
    for w in keep_ways:
        new.append(w)
    for r in keep_rel:
        # keep only members that exist in the cut map
        for m in list(r.findall("member")):
            if m.get("type") == "way" and m.get("ref") not in way_ids:
                r.remove(m)
            if m.get("type") == "relation" and m.get("ref") not in reg_ids:
                r.remove(m)
        new.append(r)
    out.write(b"<?xml version='1.0' encoding='UTF-8'?>\n" + ET.tostring(new))


def xodr(path, j, n):
    root = ET.parse(path).getroot()
    roads = {r.get("id"): r for r in root.findall("road")}
    junctions = sorted(root.findall("junction"), key=lambda x: len(x.findall("connection")))
    if j >= 0 and junctions:
        jn = junctions[min(j, len(junctions) - 1)]
        keep_j = {jn.get("id")}
        keep = []
        for c in jn.findall("connection"):
            for rid in (c.get("incomingRoad"), c.get("connectingRoad")):
                if rid in roads and rid not in keep:
                    keep.append(rid)
        keep = set(keep[:n])
    else:
        keep_j = set()
        keep = set(list(roads)[:n])
    new = ET.Element(root.tag, root.attrib)
    for child in root:
        if child.tag == "header":
            for u in child.findall("userData"):
                child.remove(u)
            new.append(child)
        elif child.tag == "road" and child.get("id") in keep:
            if child.get("junction", "-1") not in keep_j:
                child.set("junction", "-1")
            for lp in child.findall("lateralProfile"):
                child.remove(lp)
            for link in child.findall("link"):
                for end in list(link):
                    kind, ref = end.get("elementType"), end.get("elementId")
                    if (kind == "road" and ref not in keep) or (kind == "junction" and
                                                                 ref not in keep_j):
                        link.remove(end)
            new.append(child)
        elif child.tag == "junction" and child.get("id") in keep_j:
            for c in child.findall("connection"):
                if c.get("incomingRoad") not in keep or c.get("connectingRoad") not in keep:
                    child.remove(c)
            new.append(child)
    for e in new.iter():  # 1.6740308465599534e+0 -> 1.67403085
        for k, v in e.attrib.items():
            try:
                e.set(k, "%.9g" % float(v)) if any(ch in v for ch in ".e") else None
            except ValueError:
                pass
    ET.indent(new, space=" ")
    out.write(b"<?xml version='1.0' encoding='UTF-8'?>\n" + ET.tostring(new))


def main(argv):
    kind, path = argv[1], argv[2]
    if kind == "lsm-json":
        lsm_json(path, int(argv[3]))
    elif kind == "vector-map-json":
        vector_map_json(path, int(argv[3]))
    elif kind == "drive-frames":
        drive_frames(path, int(argv[3]))
    elif kind == "prob":
        prob(path, int(argv[3]), int(argv[4]))
    elif kind in ("ply", "pcd"):
        cloud(path, int(argv[3]), kind)
    elif kind == "osm":
        osm(path, int(argv[3]))
    elif kind == "xodr":
        xodr(path, int(argv[3]), int(argv[4]))
    else:
        sys.exit("shrink.py: unknown kind " + kind)


if __name__ == "__main__":
    main(sys.argv)
