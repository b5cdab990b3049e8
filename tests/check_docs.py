#!/usr/bin/python3
"""The manual against the code: README.md and docs/*.md.

- every relative link (and image) names a file that exists, and a #section that exists in it
  (GitHub's heading anchors);
- docs/commands.md holds, for every command `gonio --help` lists, the block `gonio CMD --help`
  prints (between <!-- usage:begin CMD --> and <!-- usage:end -->);
- docs/configuration.md's key table is what `gonio keys --markdown` prints.

Usage: check_docs.py GONIO [--update]   (--update rewrites the generated blocks)
"""
import argparse
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def slug(heading):
    s = heading.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)  # GitHub keeps letters, digits, _, - and spaces
    return s.replace(" ", "-")


def anchors(path):
    out, seen = set(), {}
    in_code = False
    for line in open(path, encoding="utf-8"):
        if line.startswith("```"):
            in_code = not in_code
        if in_code or not line.startswith("#"):
            continue
        base = slug(line.lstrip("#"))
        n = seen.get(base, 0)
        seen[base] = n + 1
        out.add(base if n == 0 else f"{base}-{n}")
    return out


def pages():
    yield os.path.join(ROOT, "README.md")
    for name in sorted(os.listdir(os.path.join(ROOT, "docs"))):
        if name.endswith(".md"):
            yield os.path.join(ROOT, "docs", name)


def check_links():
    problems = []
    for page in pages():
        text = open(page, encoding="utf-8").read()
        text = re.sub(r"```.*?```", "", text, flags=re.S)  # code is not links
        for target in LINK.findall(text):
            if re.match(r"[a-z]+:", target):
                continue  # http:, https:, mailto:
            path, _, anchor = target.partition("#")
            full = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
            where = os.path.relpath(page, ROOT)
            if not os.path.exists(full):
                problems.append(f"{where}: link to a missing file: {target}")
            elif anchor and full.endswith(".md") and anchor not in anchors(full):
                problems.append(f"{where}: link to a missing section: {target}")
    return problems


def run(gonio, *args):
    out = subprocess.run([gonio, *args], capture_output=True, text=True, check=True).stdout
    return out.replace(gonio, "gonio")


def commands(gonio):
    text = run(gonio, "--help")
    listing = text.split("Subcommands:", 1)[1]
    return [line.split()[0] for line in listing.splitlines() if line.startswith("  ") and line.split()]


def generated_blocks(gonio):
    """(file, begin marker, end marker, text) of every generated block."""
    blocks = []
    for cmd in commands(gonio):
        usage = run(gonio, cmd, "--help").rstrip() + "\n"
        blocks.append(("docs/commands.md", f"<!-- usage:begin {cmd} -->\n", "<!-- usage:end -->",
                       "```\n" + usage + "```\n"))
    blocks.append(("docs/configuration.md",
                   "<!-- keys:begin (generated: build/gonio keys --markdown) -->\n",
                   "<!-- keys:end -->", run(gonio, "keys", "--markdown")))
    return blocks


def check_blocks(gonio, update):
    problems = []
    for rel, begin, end, want in generated_blocks(gonio):
        path = os.path.join(ROOT, rel)
        text = open(path, encoding="utf-8").read()
        a = text.find(begin)
        b = text.find(end, a + len(begin)) if a >= 0 else -1
        if a < 0 or b < 0:
            problems.append(f"{rel}: no block {begin.strip()} … {end}")
            continue
        have = text[a + len(begin):b]
        if have != want:
            if update:
                open(path, "w", encoding="utf-8").write(text[:a + len(begin)] + want + text[b:])
            else:
                problems.append(f"{rel}: {begin.strip()} differs from what the binary prints "
                                "(tests/check_docs.py GONIO --update rewrites it)")
    return problems


def main():
    p = argparse.ArgumentParser()
    p.add_argument("gonio")
    p.add_argument("--update", action="store_true")
    a = p.parse_args()
    gonio = os.path.abspath(a.gonio)
    problems = check_blocks(gonio, a.update) + check_links()
    for line in problems:
        print("check_docs: " + line)
    if problems:
        sys.exit(1)
    print(f"check_docs: ok: links of {len(list(pages()))} pages resolve; usage of "
          f"{len(commands(gonio))} commands and the key table match the binary")


if __name__ == "__main__":
    main()
