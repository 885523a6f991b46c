"""Writes docs/GUIDE.md from docs/guide.template.md by running every `$ lacuna …` command of its
console blocks with the release binary and inserting the real output (stdout, then stderr).

The commands run in a temporary folder holding a copy of fixtures/ (as tests/guide.rs does), so
the files they write never land in the checkout. The binary is $CARGO_TARGET_DIR/release/lacuna
(target/release/lacuna without the variable)."""
import os
import shlex
import shutil
import subprocess
import sys
import tempfile

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
binary = os.path.join(os.environ.get("CARGO_TARGET_DIR", os.path.join(root, "target")), "release", "lacuna")
lines = open(os.path.join(root, "docs/guide.template.md")).read().split("\n")
out = []
with tempfile.TemporaryDirectory(prefix="lacuna-guide-") as work:
    shutil.copytree(os.path.join(root, "fixtures"), os.path.join(work, "fixtures"))
    for line in lines:
        out.append(line)
        if line.startswith("$ lacuna"):
            args = shlex.split(line[2:])[1:]
            p = subprocess.run([binary, *args], capture_output=True, text=True, cwd=work)
            text = (p.stdout + p.stderr).rstrip("\n")
            out.extend(text.split("\n"))
open(os.path.join(root, "docs/GUIDE.md"), "w").write("\n".join(out).rstrip("\n") + "\n")
print("docs/GUIDE.md written", file=sys.stderr)
