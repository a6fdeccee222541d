#!/usr/bin/env python3
"""Condense `make bench-acl`'s JSON into the tracked reference bench/acl_reference.json (issue 24).

Usage (what tools/bench/bench_acl.sh does):

    python3 tools/bench/acl_reference.py build/acl/acl_clip_bench.json bench/acl_reference.json

ACL is not packaged in Debian, so `make bench` cannot run it; it reports inbetween's side against
these recorded figures instead (tools/bench/write_results.py, "ACL 2.1 vs inbetween compression").
Per clip: joints, frames, raw float32 bytes; per error bound E: ACL's bytes at E, ACL's own error
figure, the error by inbetween's metric (and where), the bytes held to E (or the floor when ACL
cannot reach E), decode ns per joint and the compression time; plus ACL's version and commit, the
date and the machine.  ACL's side only: inbetween's figures of the same run stay in the run's own
JSON (`make bench` measures inbetween's side again, inbetween_bench_compress).  Python's standard library only; the file is written atomically.
"""

from __future__ import annotations

import json
import os
import sys
import tempfile
from pathlib import Path


def condense(doc: dict) -> dict:
    ctx = doc.get("context", {})
    keep = ("acl_version", "acl_commit", "rtm_commit", "compression_level", "error_metric", "decompression_settings",
            "decode_repetitions", "cxxflags", "inbetween_commit", "date", "machine", "command")
    out = {"about": "ACL 2.1 on the CMU clips of Debian's assimp-testmodels, by inbetween's clip-error metric; "
                    "written by `make bench-acl ACL_SRC=...` (tools/bench/bench_acl.sh), read by `make bench` "
                    "(tools/bench/write_results.py). Sizes in bytes, errors in clip units, times per joint in ns.",
           "context": {k: ctx[k] for k in keep if k in ctx},
           "clips": []}
    for clip in doc["clips"]:
        c = {k: clip[k] for k in ("clip", "joints", "frames", "fps", "raw_float32_bytes", "shell")}
        c["float32_rounding_error"] = clip["float32_rounding_error"]["max"]
        c["cases"] = []
        for case in clip["cases"]:
            acl, held = case["acl"], case["acl_held_to_error"]
            entry = {"error_bound": case["error_bound"],
                     "acl": {"bytes": acl["bytes"], "acl_error": acl["acl_error"],
                             "measured_error": acl["measured_error"],
                             "compress_seconds": acl["compress_seconds"],
                             "decode_ns_per_joint": acl["decode_ns_per_joint"]},
                     "acl_held_to_error": {k: held[k] for k in ("reached", "threshold", "bytes", "measured_error")
                                           if k in held}}
            entry["acl_held_to_error"].setdefault("reached", True)
            if "full_rotations" in held:
                entry["acl_held_to_error"]["full_rotations"] = held["full_rotations"]
            c["cases"].append(entry)
        out["clips"].append(c)
    return out


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print("usage: acl_reference.py ACL_CLIP_BENCH.json OUT.json", file=sys.stderr)
        return 2
    src, dst = Path(argv[1]), Path(argv[2])
    text = json.dumps(condense(json.loads(src.read_text(encoding="utf-8"))), indent=1, ensure_ascii=False) + "\n"
    fd, tmp = tempfile.mkstemp(dir=dst.parent, prefix=dst.name + ".", suffix=".tmp")
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        f.write(text)
    os.chmod(tmp, 0o644)
    os.replace(tmp, dst)
    print(f"acl_reference: wrote {dst}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
