#!/usr/bin/env python3
"""Runs every shell and Python snippet of the README and the docs (issue 47).

Each Markdown file's ```sh / ```python blocks run in order in one scratch folder of their own
(holding links to the repository's `fixtures/` and `examples/`), so a block reads what an
earlier block of the same page wrote; a page's Python blocks share one namespace (a later block
uses what an earlier one defined, as a reader pasting them into one session would); `flexbody` is the release binary, the `flexbody` Python
package the repository's `python/`. An HTML comment on the line before a block marks it:

    <!-- snippet: skip REASON -->         never run (reported as skipped, with the reason)
    <!-- snippet: requires MODULE -->     run only when Python can import MODULE (else skipped)

A block fails the run when it exits non-zero. The run prints each block, then
"doc snippets: N run, K skipped" and the skipped ones by name (file:line and reason).

    python3 .ci/doc_snippets.py [--list]    (--list: only print the blocks and their marks)
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The pages whose snippets a user copies: the README, the docs, the Python package's README.
PAGES = ["README.md", "python/README.md", "bench/README.md"] + sorted(
    os.path.join("docs", f) for f in os.listdir(os.path.join(ROOT, "docs")) if f.endswith(".md")
)
FENCE = re.compile(r"^(\s*)```(\w+)\s*$")
MARK = re.compile(r"^\s*<!--\s*snippet:\s*(skip|requires)\s+(.*?)\s*-->\s*$")
LANGS = {"sh": "sh", "bash": "sh", "shell": "sh", "python": "python", "py": "python"}


def blocks(page):
    """(line, language, code, mark) of each sh/python block of `page`; mark is None,
    ("skip", reason) or ("requires", module)."""
    lines = open(os.path.join(ROOT, page), encoding="utf-8").read().split("\n")
    out, k = [], 0
    while k < len(lines):
        m = FENCE.match(lines[k])
        if not m:
            k += 1
            continue
        indent, lang, start = len(m.group(1)), m.group(2).lower(), k
        body = []
        k += 1
        while k < len(lines) and lines[k].strip() != "```":
            body.append(lines[k][indent:] if lines[k][:indent].strip() == "" else lines[k])
            k += 1
        k += 1
        if lang not in LANGS:
            continue
        prev = next((lines[j] for j in range(start - 1, -1, -1) if lines[j].strip()), "")
        mark = MARK.match(prev)
        out.append((start + 1, LANGS[lang], "\n".join(body) + "\n", mark.groups() if mark else None))
    return out


def python_has(module):
    return subprocess.run([sys.executable, "-c", f"import {module}"], capture_output=True).returncode == 0


def run_python(code, name, work, namespace):
    """Runs `code` in `namespace` with `work` as the current folder: None, or the traceback."""
    import traceback
    here, path = os.getcwd(), list(sys.path)
    sys.path.insert(0, os.path.join(ROOT, "python"))
    os.chdir(work)
    try:
        exec(compile(code, name, "exec"), namespace)
        return None
    except BaseException:  # a snippet's SystemExit is a failure too
        return traceback.format_exc()[-3000:]
    finally:
        os.chdir(here)
        sys.path[:] = path


def main():
    only_list = "--list" in sys.argv[1:]
    exe = os.environ.get("FLEXBODY", os.path.join(ROOT, "target", "release", "flexbody"))
    if not only_list and not os.access(exe, os.X_OK):
        sys.exit(f"doc snippets: {exe} missing: run `cargo build --release` first")
    ran, skipped, failed = 0, [], []
    for page in PAGES:
        if not os.path.exists(os.path.join(ROOT, page)):
            continue
        found = blocks(page)
        if not found:
            continue
        work = tempfile.mkdtemp(prefix="flexbody-snippets-")
        bindir = os.path.join(work, ".bin")
        os.makedirs(bindir)
        if not only_list:
            os.symlink(exe, os.path.join(bindir, "flexbody"))
        for d in ("fixtures", "examples"):
            os.symlink(os.path.join(ROOT, d), os.path.join(work, d))
        env = dict(os.environ)
        env["PATH"] = bindir + os.pathsep + env.get("PATH", "")
        env["PYTHONPATH"] = os.path.join(ROOT, "python") + os.pathsep + env.get("PYTHONPATH", "")
        env["FLEXBODY"] = exe
        namespace = {"__name__": "__main__"}
        for line, lang, code, mark in found:
            name = f"{page}:{line} ({lang})"
            if mark and mark[0] == "skip":
                skipped.append(f"{name}: {mark[1]}")
                print(f"doc snippets: skip {name}: {mark[1]}")
                continue
            if mark and mark[0] == "requires" and (only_list or not python_has(mark[1])):
                if not only_list:
                    skipped.append(f"{name}: needs the Python module {mark[1]}")
                    print(f"doc snippets: skip {name}: needs the Python module {mark[1]}")
                    continue
            if only_list:
                print(f"doc snippets: {name}" + (f" (requires {mark[1]})" if mark else ""))
                continue
            print(f"doc snippets: run  {name}", flush=True)
            ran += 1
            if lang == "sh":
                r = subprocess.run(["bash", "-euo", "pipefail", "-c", code], cwd=work, env=env,
                                   capture_output=True, text=True)
                if r.returncode != 0:
                    failed.append(name)
                    print(f"doc snippets: FAILED {name} (exit {r.returncode})\n{code}--- stdout\n"
                          f"{r.stdout[-3000:]}--- stderr\n{r.stderr[-3000:]}")
                continue
            error = run_python(code, name, work, namespace)
            if error:
                failed.append(name)
                print(f"doc snippets: FAILED {name}\n{code}--- error\n{error}")
        shutil.rmtree(work, ignore_errors=True)
    print(f"doc snippets: {ran} run, {len(skipped)} skipped, {len(failed)} failed")
    for s in skipped:
        print(f"doc snippets: skipped {s}")
    if failed:
        sys.exit(f"doc snippets: failed: {', '.join(failed)}")


if __name__ == "__main__":
    main()
