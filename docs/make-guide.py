"""Writes docs/GUIDE.md from docs/guide.template.md by running every `$ lacuna …` command of its
console blocks with the release binary and inserting the real output (stdout, then stderr)."""
import shlex
import subprocess
import sys

lines = open("docs/guide.template.md").read().split("\n")
out = []
for line in lines:
    out.append(line)
    if line.startswith("$ lacuna"):
        args = shlex.split(line[2:])[1:]
        p = subprocess.run(["target/release/lacuna", *args], capture_output=True, text=True)
        text = (p.stdout + p.stderr).rstrip("\n")
        out.extend(text.split("\n"))
open("docs/GUIDE.md", "w").write("\n".join(out).rstrip("\n") + "\n")
print("docs/GUIDE.md written", file=sys.stderr)
