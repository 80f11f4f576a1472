#!/usr/bin/python3
"""Checks GeoJSON files with GEOS (Debian's python3-shapely): every feature's geometry must be
valid (shapely.validation.explain_validity == "Valid Geometry") and every polygon's exterior
ring counter-clockwise, interior rings clockwise (RFC 7946 section 3.1.6).

usage: scripts/check-geojson.py FILE.geojson...
Prints one line per file ("<file>: <n> features, <k> polygons, 0 invalid, 0 clockwise") and
every problem found; exits 1 when any feature is invalid or wound the wrong way, 2 on bad use.
"""
import json
import sys

try:
    from shapely.geometry import LinearRing, shape
    from shapely.validation import explain_validity
except ImportError:  # pragma: no cover - the test skips when shapely is absent
    print("check-geojson: python3-shapely is not installed", file=sys.stderr)
    sys.exit(77)


def check(path):
    with open(path) as f:
        doc = json.load(f)
    features = doc.get("features", [])
    invalid = wound = polygons = 0
    for feature in features:
        fid = feature.get("id")
        geom = feature["geometry"]
        why = explain_validity(shape(geom))
        if why != "Valid Geometry":
            invalid += 1
            print(f"{path}: feature {fid} ({geom['type']}): {why}")
        if geom["type"] == "Polygon":
            polygons += 1
            rings = geom["coordinates"]
            if not LinearRing([c[:2] for c in rings[0]]).is_ccw:
                wound += 1
                print(f"{path}: feature {fid}: exterior ring is clockwise")
            for hole in rings[1:]:
                if LinearRing([c[:2] for c in hole]).is_ccw:
                    wound += 1
                    print(f"{path}: feature {fid}: interior ring is counter-clockwise")
    print(f"{path}: {len(features)} features, {polygons} polygons, {invalid} invalid, "
          f"{wound} clockwise")
    return invalid == 0 and wound == 0 and len(features) > 0


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    ok = all([check(p) for p in argv[1:]])
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
