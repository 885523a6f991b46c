"""Runs the README's Python block as a new user would, and checks what it prints.

Usage: python run_readme.py README.md (run from an empty folder: the block writes f0.svg).
Every `print(...)` line of the block that ends in a `# comment` must print exactly that comment;
the block must run without an exception. .ci/run runs this in a fresh virtual environment that
holds only the built wheel and the dependencies it declares, so a dependency the README needs but
the package does not declare fails here (issue #33: sympy was missing)."""
import contextlib
import io
import re
import sys

text = open(sys.argv[1], encoding="utf-8").read()
blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
if not blocks:
    sys.exit("no ```python block in the README")
code = blocks[0]
expected = [
    line.split("#", 1)[1].strip()
    for line in code.splitlines()
    if line.startswith("print(") and "#" in line
]
out = io.StringIO()
with contextlib.redirect_stdout(out):
    exec(compile(code, "README.md", "exec"), {})
printed = [line.strip() for line in out.getvalue().splitlines()]
if printed != expected:
    sys.exit(f"the README's Python block printed {printed}, its comments say {expected}")
print(f"README Python block: ran, and printed what its comments say ({len(printed)} lines)")
