"""The tests use only what is in the repository (issue 19): a clone with nothing beside it
must pass them. Fails when a test file refers to a path outside the repository (the HexMe
set beside this team's clones, a home folder) or to a HexMe model that tests/data/hexme does
not carry.

    python3 tests/self_contained.py <repository>
"""
import os
import re
import sys

OUTSIDE = [re.compile(p) for p in (r"\.\./shared", r"shared/models", r"/work/", r"/home/\w")]
# HexMe model names (i15o_s8, s07o_notch, ...) as the tests spell them.
MODEL = re.compile(r"\b([ins]\d\do_\w+?)(?:\.step)?\b")


def main(repo):
    tests = os.path.join(repo, "tests")
    data = os.path.join(tests, "data", "hexme")
    carried = {f[:-5] for f in os.listdir(data) if f.endswith(".step")}
    problems = []
    checked = 0
    for root, dirs, files in os.walk(tests):
        dirs[:] = [d for d in dirs if d not in ("data", "__pycache__")]
        for name in files:
            if not name.endswith((".cpp", ".h", ".py", ".txt", ".sh")) or name == "self_contained.py":
                continue
            path = os.path.join(root, name)
            with open(path, encoding="utf-8", errors="replace") as f:
                for number, line in enumerate(f, 1):
                    where = "{}:{}".format(os.path.relpath(path, repo), number)
                    for pattern in OUTSIDE:
                        if pattern.search(line):
                            problems.append("{} refers outside the repository: {}".format(
                                where, line.strip()))
                    for model in MODEL.findall(line):
                        if model not in carried and model.split(".")[0] not in carried:
                            problems.append("{} needs HexMe model {}, which tests/data/hexme "
                                            "does not carry".format(where, model))
            checked += 1
    for p in problems:
        print(p)
    print("self_contained: {} test files checked, {} HexMe models carried, {} problems".format(
        checked, len(carried), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
