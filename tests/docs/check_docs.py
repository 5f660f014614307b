#!/usr/bin/env python3
"""The docs' references hold: every citation of docs/DESIGN.md, every repository path a doc names
and every relative Markdown link resolves. Standard library only.

    check_docs.py SOURCE_DIR         exit 0 when every reference resolves, 1 naming each broken one
                                     as file:line: what
    check_docs.py --self-test        builds a small tree with one good and one bad reference of each
                                     kind and checks that the checker tells them apart

What is checked
  1. Citations of docs/DESIGN.md in any source, build, script or doc file: `DESIGN.md "Section"`
     (one or more quoted names, separated by commas; the quotes may span comment lines) must be a
     heading of docs/DESIGN.md, word for word; `DESIGN.md step N` (or `"Section", step N`) must be
     a numbered step there (in the named section when one is named).
  2. Repository paths in the top-level *.md and docs/*.md: a token that starts with one of the
     top-level folders (core/ dicom/ db/ server/ client/ clients/ proto/ bench/ tests/ fuzz/
     docker/ docs/ scripts/ tools/ cmake/) must name a file or folder of the checkout. Globs
     (`db/sql/sql_store_*.cpp`) must match at least one; `{h,cpp}` expands to each; a path without
     an extension may name a file pair by its stem (`proto/text/feature_expression`).
  3. Relative Markdown links [text](path#anchor) in the same files: the file must exist and, for a
     Markdown file, the anchor must be one of its headings (GitHub's slugs).
The checkout's files are git's (tracked and untracked-but-not-ignored) when SOURCE_DIR is a git
work tree, else every file outside build folders, so a build tree never makes a path "exist".
"""

import fnmatch
import os
import re
import subprocess
import sys
import tempfile

TOP_DIRS = ("core", "dicom", "db", "server", "client", "clients", "proto", "bench", "tests", "fuzz", "docker",
            "docs", "scripts", "tools", "cmake")
CITING_EXTENSIONS = {".h", ".hpp", ".cpp", ".cc", ".py", ".cmake", ".md", ".proto", ".sh", ".txt", ".yaml", ".yml"}
SKIPPED_TREES = ("tests/data/", "fuzz/corpus/", "fuzz/regressions/")
SELF = "tests/docs/check_docs.py"


# ---------------------------------------------------------------------------------------------
# The checkout


def list_files(root):
    """Relative paths of the checkout's files (posix separators)."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "--cached", "--others", "--exclude-standard", "-z"],
                             capture_output=True, check=True)
        top = subprocess.run(["git", "-C", root, "rev-parse", "--show-toplevel"], capture_output=True, text=True,
                             check=True).stdout.strip()
        if os.path.realpath(top) == os.path.realpath(root):
            files = [p for p in out.stdout.decode("utf-8", "replace").split("\0") if p]
            return sorted(p for p in set(files) if os.path.isfile(os.path.join(root, p)))
    except (OSError, subprocess.CalledProcessError):
        pass
    files = []
    for dirpath, dirnames, filenames in os.walk(root):
        rel = os.path.relpath(dirpath, root)
        dirnames[:] = [d for d in dirnames
                       if not (d.startswith(".") or d.startswith("build") or d in ("node_modules", "var", "out"))]
        for name in filenames:
            files.append(name if rel == "." else rel.replace(os.sep, "/") + "/" + name)
    return sorted(files)


class Tree:
    def __init__(self, root):
        self.root = root
        self.files = list_files(root)
        self.file_set = set(self.files)
        self.dirs = set()
        for f in self.files:
            parts = f.split("/")[:-1]
            for i in range(1, len(parts) + 1):
                self.dirs.add("/".join(parts[:i]))

    def read(self, rel):
        try:
            with open(os.path.join(self.root, rel), encoding="utf-8") as f:
                return f.read()
        except (OSError, UnicodeDecodeError):
            return None

    def exists(self, rel, want_dir=False):
        rel = rel.rstrip("/")
        if not rel:
            return True
        if "*" in rel or "?" in rel:
            return self._glob(rel, want_dir)
        if rel in self.dirs:
            return True
        if want_dir:
            return False
        if rel in self.file_set:
            return True
        # A file pair named by its stem: `server/app/grid_choice` for grid_choice.{h,cpp}.
        last = rel.rsplit("/", 1)[-1]
        if "." not in last:
            prefix = rel + "."
            return any(f.startswith(prefix) and "/" not in f[len(prefix):] for f in self.files)
        return False

    def _glob(self, pattern, want_dir):
        parts = pattern.split("/")
        candidates = list(self.dirs) if want_dir else list(self.dirs) + self.files
        for c in candidates:
            cp = c.split("/")
            if len(cp) == len(parts) and all(fnmatch.fnmatchcase(a, b) for a, b in zip(cp, parts)):
                return True
        return False


def doc_files(tree):
    """The docs whose paths and links are checked: top-level *.md and docs/*.md."""
    return [f for f in tree.files if f.endswith(".md") and ("/" not in f or re.fullmatch(r"docs/[^/]+\.md", f))]


def citing_files(tree):
    out = []
    for f in tree.files:
        if f == SELF or f.startswith(SKIPPED_TREES):
            continue
        name = f.rsplit("/", 1)[-1]
        ext = os.path.splitext(name)[1]
        if ext in CITING_EXTENSIONS or name == "CMakeLists.txt":
            out.append(f)
        elif "." not in name:
            text = tree.read(f)
            if text is not None and text.startswith("#!"):
                out.append(f)
    return out


# ---------------------------------------------------------------------------------------------
# Markdown


def headings(text):
    """(title, slug, line) of every ATX heading outside fenced code."""
    out, fenced, slugs = [], False, {}
    for n, line in enumerate(text.splitlines(), 1):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        m = None if fenced else re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
        if m:
            title = " ".join(m.group(2).split())
            slug = github_slug(title)
            count = slugs.get(slug, 0)
            slugs[slug] = count + 1
            out.append((title, slug if count == 0 else f"{slug}-{count}", n))
    return out


def github_slug(title):
    s = title.strip().lower()
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def numbered_steps(text):
    """{section title: set of step numbers}: top-level numbered list items under each heading."""
    steps, current, fenced = {}, None, False
    for line in text.splitlines():
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if fenced:
            continue
        m = re.match(r"^#{1,6}\s+(.*?)\s*#*\s*$", line)
        if m:
            current = " ".join(m.group(1).split())
            steps.setdefault(current, set())
            continue
        m = re.match(r"^(\d+)\.\s", line)
        if m:
            steps.setdefault(current, set()).add(int(m.group(1)))
    return steps


# ---------------------------------------------------------------------------------------------
# 1. Citations of docs/DESIGN.md

COMMENT_LEAD = re.compile(r"^\s*(?://+|#+|\*+|--|>|;)?\s*")
CITATION = re.compile(r"(?<![\w-])((?:docs/)?)DESIGN\.md")


def citations(text):
    """(line, with docs/ in front?, [section names], [step numbers]) for each citation of DESIGN.md."""
    lines = text.splitlines()
    out = []
    for n, line in enumerate(lines, 1):
        for m in CITATION.finditer(line):
            follow = [line[m.end():]] + [COMMENT_LEAD.sub("", l, count=1) for l in lines[n:n + 3]]
            rest = " ".join(s.strip() for s in follow)
            rest = re.sub(r"^(?:\]\([^)]*\)|`|\*)+", "", rest)  # the end of a link or code span
            rest = re.sub(r"^\s*,?\s*", "", rest)
            sections, steps = [], []
            while True:
                q = re.match(r"[\"\u201c]([^\"\u201d]+)[\"\u201d]\s*[,;]?\s*", rest)
                if q:
                    sections.append(" ".join(q.group(1).split()))
                    rest = rest[q.end():]
                    continue
                s = re.match(r"steps?\s+(\d+)((?:\s*(?:,|and|to|-|\u2013)\s*\d+)*)", rest)
                if s:
                    steps += [int(x) for x in re.findall(r"\d+", s.group(0))]
                break
            out.append((n, bool(m.group(1)), sections, steps))
    return out


def check_citations(tree):
    problems = []
    design = tree.read("docs/DESIGN.md")
    if design is None:
        return [("docs/DESIGN.md", 0, "missing, and sources cite it")] if any(
            citations(tree.read(f) or "") for f in citing_files(tree)) else []
    titles = {t for t, _, _ in headings(design)}
    steps = numbered_steps(design)
    all_steps = set().union(*steps.values()) if steps else set()
    for f in citing_files(tree):
        text = tree.read(f)
        if text is None or "DESIGN.md" not in text:
            continue
        for line, qualified, sections, step_numbers in citations(text):
            # A comment must say where the file is; a Markdown mention of the page (README's layout)
            # need not, but a citation of a section from outside docs/ must.
            cites = sections or step_numbers
            if not qualified and not f.startswith("docs/") and (cites or not f.endswith(".md")):
                problems.append((f, line, "cites DESIGN.md without its folder: write docs/DESIGN.md"))
            for s in sections:
                if s not in titles:
                    problems.append((f, line, f'cites docs/DESIGN.md "{s}", which has no such heading'))
            known = set().union(*(steps.get(s, set()) for s in sections)) if sections else all_steps
            for k in step_numbers:
                if k not in known:
                    where = f' "{sections[0]}"' if sections else ""
                    problems.append((f, line, f"cites docs/DESIGN.md{where} step {k}, which has no such step"))
    return problems


# ---------------------------------------------------------------------------------------------
# 2. Repository paths named in the docs

SEGMENT = r"(?:[\w.*?+\-]|\{[\w.,]+\})+"
REPO_PATH = re.compile(r"(?<![\w./\-~$@:])((?:" + "|".join(TOP_DIRS) + r")/(?:" + SEGMENT + r"/?)*)")


def expand_braces(path):
    m = re.search(r"\{([^{}]*)\}", path)
    if not m:
        return [path]
    out = []
    for alt in m.group(1).split(","):
        out += expand_braces(path[:m.start()] + alt + path[m.end():])
    return out


def repo_paths(line):
    """The repository paths a line of prose or code names."""
    out = []
    for m in REPO_PATH.finditer(line):
        token = m.group(1)
        # Prose punctuation after a path is not part of it; neither is an ellipsis.
        out.append(re.sub(r"[.,:;]+$", "", token))
    return out


def check_paths(tree):
    problems = []
    for f in doc_files(tree):
        text = tree.read(f)
        if text is None:
            continue
        for n, line in enumerate(text.splitlines(), 1):
            for token in repo_paths(line):
                for path in expand_braces(token):
                    if not tree.exists(path, want_dir=path.endswith("/")):
                        problems.append((f, n, f"names `{path}`, which is not in the repository"))
    return problems


# File names alone, in backticks (`grid_choice.h`): some file of the repository has that name.
FILE_NAME = re.compile(r"`([\w*?+\-]+(?:\.[\w*?+\-]+)*\.(?:h|hpp|cpp|cc|py|sh|md|proto|cmake))`")


def check_file_names(tree):
    problems = []
    names = {f.rsplit("/", 1)[-1] for f in tree.files}
    for f in doc_files(tree):
        text = tree.read(f)
        if text is None:
            continue
        for n, line in enumerate(text.splitlines(), 1):
            for m in FILE_NAME.finditer(line):
                if not any(fnmatch.fnmatchcase(name, m.group(1)) for name in names):
                    problems.append((f, n, f"names `{m.group(1)}`, and no file of the repository has that name"))
    return problems


# ---------------------------------------------------------------------------------------------
# 3. Relative Markdown links

LINK = re.compile(r"(?<!!)\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)|!\[[^\]]*\]\(([^)\s]+)\)")


def check_links(tree):
    problems = []
    for f in doc_files(tree):
        text = tree.read(f)
        if text is None:
            continue
        fenced = False
        base = os.path.dirname(f)
        for n, line in enumerate(text.splitlines(), 1):
            if line.lstrip().startswith("```"):
                fenced = not fenced
                continue
            if fenced:
                continue
            code_free = re.sub(r"`[^`]*`", "", line)
            for m in LINK.finditer(code_free):
                target = m.group(1) or m.group(2)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # https:, mailto:, ...
                    continue
                path, _, anchor = target.partition("#")
                rel = f if not path else os.path.normpath(os.path.join(base, path)).replace(os.sep, "/")
                if rel.startswith("../") or rel == "..":
                    problems.append((f, n, f"links to `{target}`, outside the repository"))
                    continue
                if path and not tree.exists(rel, want_dir=path.endswith("/")):
                    problems.append((f, n, f"links to `{target}`, and `{rel}` is not in the repository"))
                    continue
                if anchor and rel.endswith(".md"):
                    linked = tree.read(rel) or ""
                    if anchor not in {s for _, s, _ in headings(linked)}:
                        problems.append((f, n, f"links to `{target}`, and {rel} has no heading #{anchor}"))
    return problems


# ---------------------------------------------------------------------------------------------


def check(root):
    tree = Tree(root)
    return sorted(set(check_citations(tree) + check_paths(tree) + check_file_names(tree) + check_links(tree)))


def self_test():
    """One good and one bad reference of each kind; the checker must flag exactly the bad ones."""
    files = {
        "docs/DESIGN.md": "# design\n\n## Good section\n\n1. first step\n2. second step\n\n## Other, with comma\n",
        # citations: line 1 good section, 2 bad section, 3 good step, 4 bad step, 5-6 a good
        # section across comment lines, 7 a good section whose step is bad, 8 no docs/ in front
        "core/a.h": ('// (docs/DESIGN.md "Good section")\n'
                     '// (docs/DESIGN.md "Missing section")\n'
                     "// (docs/DESIGN.md step 2)\n"
                     "// (docs/DESIGN.md step 9)\n"
                     '// (docs/DESIGN.md, "Other,\n'
                     '// with comma")\n'
                     '# docs/DESIGN.md "Good section", step 3\n'
                     '// (DESIGN.md "Good section") without its folder\n'),
        "core/b_one.cpp": "",
        "core/b_one.h": "",
        # paths: line 1 good file, 2 missing file, 3 good glob, 4 glob matching nothing, 5 good
        # braces, 6 braces with one missing, 7 good stem and folder, 8 missing folder;
        # links: 9 good, 10 missing file, 11 good anchor, 12 missing anchor, 14 not a link (code);
        # file names alone: 16 good ones, 17 a missing one (and, inside docs/, a bare citation)
        "docs/GUIDE.md": ("See `core/a.h`.\n"
                          "See `core/missing.h`.\n"
                          "See core/b_*.cpp, and\n"
                          "see core/zz_*.cpp.\n"
                          "See `core/b_one.{h,cpp}`.\n"
                          "See `core/a.{h,cpp}`.\n"
                          "See `core/b_one` in core/.\n"
                          "See server/.\n"
                          "[a](../core/a.h)\n"
                          "[b](NOPE.md)\n"
                          "[c](DESIGN.md#good-section)\n"
                          "[d](DESIGN.md#bad-section)\n"
                          "```\nnot a link [x](nowhere.md)\n```\n"
                          "File names alone: `b_one.cpp`, `b_*.h`, and\n"
                          "`nowhere_at_all.cpp`; a design of its own: DESIGN.md \"Good section\".\n"),
        # line 1: a good link, a URL that is not a path; line 2: DESIGN.md mentioned, fine in a doc;
        # line 3: a section cited without docs/ from outside docs/
        "README.md": ("Read [the guide](docs/GUIDE.md) and https://example.org/core/missing.h.\n"
                      "docs/  DESIGN.md (the design)\n"
                      'See DESIGN.md "Good section".\n'),
        "build/core/missing.h": "",  # a build tree never makes a path exist
    }
    expected = {
        ("core/a.h", 2), ("core/a.h", 4), ("core/a.h", 7), ("core/a.h", 8),
        ("docs/GUIDE.md", 2), ("docs/GUIDE.md", 4), ("docs/GUIDE.md", 6), ("docs/GUIDE.md", 8),
        ("docs/GUIDE.md", 10), ("docs/GUIDE.md", 12), ("docs/GUIDE.md", 17), ("README.md", 3),
    }
    with tempfile.TemporaryDirectory() as root:
        for rel, text in files.items():
            path = os.path.join(root, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        found = check(root)
    got = {(f, n) for f, n, _ in found}
    ok = True
    for f, n in sorted(expected - got):
        print(f"self-test: the bad reference at {f}:{n} was not flagged", file=sys.stderr)
        ok = False
    for f, n, what in found:
        if (f, n) not in expected:
            print(f"self-test: the good reference at {f}:{n} was flagged: {what}", file=sys.stderr)
            ok = False
    if ok:
        print(f"self-test: {len(expected)} bad references flagged, every good one passed")
    return 0 if ok else 1


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    problems = check(argv[1])
    for f, n, what in problems:
        print(f"{f}:{n}: {what}")
    sys.stdout.flush()
    if problems:
        print(f"{len(problems)} broken references (tests/docs/check_docs.py)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
