#!/usr/bin/env python3
"""Keeps the front page short and the documentation's links whole (issue 56).

    python3 tests/docs/check_docs.py SOURCE_DIR

Prints one line per finding, `file:line: what`, and exits 1 when there is any:

- README.md longer than 150 lines;
- a Markdown prose line (not in a fenced code block, not a table row) longer
  than 200 characters in README.md, docs/status.md or docs/tutorials/*.md;
- a cell of docs/status.md's table longer than 35 words;
- a relative link in any *.md of the repository (build*/ and hidden folders
  left out) to a file or folder that does not exist.

Links into docs/tutorials/ are not checked while that folder does not exist
(the tutorials are written in their own change); once it exists they are.
Anchors (`#section`) are not checked, only the file they are in.
Python 3, standard library only.
"""
import os
import re
import sys

README_MAX_LINES = 150
PROSE_MAX_CHARS = 200
STATUS_CELL_MAX_WORDS = 35

FENCE = re.compile(r"^\s{0,3}(```|~~~)")
INLINE_CODE = re.compile(r"(`+)(.+?)\1")
# [text](target "title") and ![alt](target); the text may hold one level of
# brackets (a badge or an image inside a link).
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*(<[^>]*>|[^)\s]+)(?:\s+[\"'(][^)]*)?\)")
REFERENCE_DEFINITION = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)")
HTML_LINK = re.compile(r"<(?:a|img)\s[^>]*?(?:href|src)\s*=\s*\"([^\"]+)\"", re.IGNORECASE)
SCHEME = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def markdown_lines(path):
    """(line number, text, in_fence) for every line of a Markdown file."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    fence = None
    for number, line in enumerate(lines, 1):
        match = FENCE.match(line)
        if match:
            marker = match.group(1)
            if fence is None:
                fence = marker
                yield number, line, True
                continue
            if marker == fence:
                fence = None
                yield number, line, True
                continue
        yield number, line, fence is not None


def is_table_row(line):
    return line.lstrip().startswith("|")


def markdown_files(root):
    for directory, subdirs, files in os.walk(root):
        subdirs[:] = sorted(d for d in subdirs
                            if not d.startswith(".") and not d.startswith("build")
                            and d != "node_modules")
        for name in sorted(files):
            if name.endswith(".md"):
                yield os.path.join(directory, name)


def check_readme_length(root, findings):
    path = os.path.join(root, "README.md")
    if not os.path.exists(path):
        findings.append("README.md:1: missing")
        return
    count = sum(1 for _ in markdown_lines(path))
    if count > README_MAX_LINES:
        findings.append(f"README.md:{README_MAX_LINES + 1}: {count} lines, at most "
                        f"{README_MAX_LINES} (the front page; details go to docs/ or a folder's README)")


def check_prose_lines(root, relative, findings):
    path = os.path.join(root, relative)
    if not os.path.exists(path):
        return
    for number, line, in_fence in markdown_lines(path):
        if in_fence or is_table_row(line):
            continue
        if len(line) > PROSE_MAX_CHARS:
            findings.append(f"{relative}:{number}: prose line of {len(line)} characters, "
                            f"at most {PROSE_MAX_CHARS} (wrap at ~100)")


def table_cells(line):
    text = line.strip()
    if text.startswith("|"):
        text = text[1:]
    if text.endswith("|") and not text.endswith("\\|"):
        text = text[:-1]
    # split on | that is neither escaped nor inside inline code
    cells, current, in_code = [], "", False
    i = 0
    while i < len(text):
        c = text[i]
        if c == "\\" and i + 1 < len(text):
            current += text[i:i + 2]
            i += 2
            continue
        if c == "`":
            in_code = not in_code
        if c == "|" and not in_code:
            cells.append(current)
            current = ""
        else:
            current += c
        i += 1
    cells.append(current)
    return [cell.strip() for cell in cells]


def check_status_cells(root, findings):
    relative = os.path.join("docs", "status.md")
    path = os.path.join(root, relative)
    if not os.path.exists(path):
        findings.append(f"{relative}:1: missing (the status table, issue 56)")
        return
    for number, line, in_fence in markdown_lines(path):
        if in_fence or not is_table_row(line):
            continue
        for column, cell in enumerate(table_cells(line), 1):
            if re.fullmatch(r":?-{3,}:?", cell):
                continue
            words = len(cell.split())
            if words > STATUS_CELL_MAX_WORDS:
                findings.append(f"{relative}:{number}: cell {column} has {words} words, at most "
                                f"{STATUS_CELL_MAX_WORDS} (the figures go to the README the row links)")


def link_targets(line):
    text = INLINE_CODE.sub("", line)
    for match in INLINE_LINK.finditer(text):
        yield match.group(1)
    match = REFERENCE_DEFINITION.match(text)
    if match:
        yield match.group(1)
    for match in HTML_LINK.finditer(text):
        yield match.group(1)


def check_links(root, findings):
    tutorials = os.path.join(root, "docs", "tutorials")
    tutorials_exist = os.path.isdir(tutorials)
    checked = files = 0
    for path in markdown_files(root):
        files += 1
        relative = os.path.relpath(path, root)
        for number, line, in_fence in markdown_lines(path):
            if in_fence:
                continue
            for target in link_targets(line):
                target = target.strip("<>")
                if not target or target.startswith("#") or SCHEME.match(target):
                    continue
                file_part = target.split("#", 1)[0].split("?", 1)[0]
                if not file_part:
                    continue
                if file_part.startswith("/"):
                    resolved = os.path.join(root, file_part.lstrip("/"))
                else:
                    resolved = os.path.join(os.path.dirname(path), file_part)
                resolved = os.path.normpath(resolved)
                if not tutorials_exist and (resolved == tutorials
                                            or resolved.startswith(tutorials + os.sep)):
                    continue
                checked += 1
                if not os.path.exists(resolved):
                    findings.append(f"{relative}:{number}: link to {target}: no such file "
                                    f"({os.path.relpath(resolved, root)})")
    return files, checked


def main(argv):
    if len(argv) != 2:
        print("usage: check_docs.py SOURCE_DIR", file=sys.stderr)
        return 2
    root = os.path.abspath(argv[1])
    findings = []
    check_readme_length(root, findings)
    prose = ["README.md", os.path.join("docs", "status.md")]
    tutorials = os.path.join(root, "docs", "tutorials")
    if os.path.isdir(tutorials):
        prose += [os.path.join("docs", "tutorials", name)
                  for name in sorted(os.listdir(tutorials)) if name.endswith(".md")]
    for relative in prose:
        check_prose_lines(root, relative, findings)
    check_status_cells(root, findings)
    files, checked = check_links(root, findings)
    for finding in findings:
        print(finding)
    if findings:
        print(f"check_docs: {len(findings)} finding(s)", file=sys.stderr)
        return 1
    note = "" if os.path.isdir(tutorials) else "; docs/tutorials/ not there yet: links into it not checked"
    print(f"check_docs: ok ({files} Markdown files, {checked} relative links{note})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
