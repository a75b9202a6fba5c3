#!/usr/bin/env python3
"""Checks the files that make the repository an Arduino and a PlatformIO
library against the source tree:

- library.properties has every field the Arduino 1.5 library format requires,
  and library.properties, library.json, include/lsc/version.h (its macros and
  its string) and CMake agree on the version;
- every public header include/lsc/X.h has its forwarder src/lsc/X.h (the
  Arduino IDE puts only src/ on the include path);
- library.json's srcFilter selects exactly the portable sources (core,
  client, lxclient, sim, player, units) and the Arduino wrapper, never the host-only serial transport.

usage: check_library_files.py ROOT CMAKE_PROJECT_VERSION
"""
import fnmatch
import json
import os
import sys

root, cmake_version = sys.argv[1], sys.argv[2]
failures = []


def fail(msg):
    failures.append(msg)


props = {}
with open(os.path.join(root, "library.properties"), encoding="utf-8") as f:
    for line in f:
        line = line.strip()
        if line and not line.startswith("#"):
            key, _, value = line.partition("=")
            props[key] = value
for key in ("name", "version", "author", "maintainer", "sentence", "paragraph", "category",
            "url", "architectures"):
    if not props.get(key):
        fail(f"library.properties: no {key}")

with open(os.path.join(root, "library.json"), encoding="utf-8") as f:
    lib = json.load(f)
for where, version in (("library.properties", props.get("version")),
                       ("library.json", lib.get("version"))):
    if version != cmake_version:
        fail(f"{where}: version {version}, CMake project version {cmake_version}")

macros = {}
with open(os.path.join(root, "include", "lsc", "version.h"), encoding="utf-8") as f:
    for line in f:
        words = line.split()
        if len(words) >= 3 and words[0] == "#define" and words[1].startswith("LSC_VERSION_"):
            macros[words[1]] = words[2].strip('"')
parts = "%s.%s.%s" % (macros.get("LSC_VERSION_MAJOR"), macros.get("LSC_VERSION_MINOR"),
                      macros.get("LSC_VERSION_PATCH"))
for what, version in (("LSC_VERSION_MAJOR/MINOR/PATCH", parts),
                      ("LSC_VERSION_STRING", macros.get("LSC_VERSION_STRING"))):
    if version != cmake_version:
        fail(f"include/lsc/version.h: {what} {version}, CMake project version {cmake_version}")

for name in sorted(os.listdir(os.path.join(root, "include", "lsc"))):
    if not name.endswith(".h"):
        continue
    fwd = os.path.join(root, "src", "lsc", name)
    want = f'#include "../../include/lsc/{name}"'
    if not os.path.exists(fwd) or want not in open(fwd, encoding="utf-8").read():
        fail(f"src/lsc/{name}: missing, or does not forward to include/lsc/{name}")

# PlatformIO's srcFilter: "+<glob>" adds, "-<glob>" removes, in order, paths
# relative to srcDir.
src_dir = os.path.join(root, lib["build"]["srcDir"])
all_src = []
for dirpath, _, files in os.walk(src_dir):
    for name in files:
        if name.endswith((".c", ".cpp", ".S")):
            all_src.append(os.path.relpath(os.path.join(dirpath, name), src_dir))
selected = set()
for rule in lib["build"]["srcFilter"]:
    sign, pattern = rule[0], rule[2:-1]
    for path in all_src:
        if fnmatch.fnmatch(path, pattern) or fnmatch.fnmatch(path, pattern + "/*"):
            if sign == "+":
                selected.add(path)
            else:
                selected.discard(path)
portable = {p for p in all_src if p.split("/")[0] in ("core", "client", "lxclient", "sim", "player", "units")} | {"LSC.cpp"}
for path in sorted(portable - selected):
    fail(f"library.json: srcFilter leaves out {path}")
for path in sorted(selected - portable):
    fail(f"library.json: srcFilter takes {path}, which is not portable")
if not any(p.startswith("core/") for p in selected):
    fail("library.json: srcFilter selects no core source")

for msg in failures:
    print("FAIL:", msg)
print(f"{len(selected)} sources selected; {len(failures)} problem(s)")
sys.exit(1 if failures else 0)
