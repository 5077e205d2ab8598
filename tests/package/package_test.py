# The Debian package (issue 24): builds it with CPack from this build tree, checks its
# control data (FreeCAD, OCCT and Python declared as dependencies, each a package name dpkg
# knows), unpacks it into a scratch root with `dpkg -x` (no change to the system), and runs
# freecadcmd against the unpacked Mod folder: `import VoroHex` must load the module from the
# package, not from the build tree, and mesh a box. Exit 0 = pass.
#   python3 package_test.py <build dir>
import glob
import os
import subprocess
import sys
import tempfile

build = os.path.abspath(sys.argv[1])


def check(cond, what):
    if not cond:
        print("package_test: FAIL: " + what)
        sys.exit(1)
    print("package_test: ok: " + what)


with tempfile.TemporaryDirectory(prefix="vorohex-deb-") as tmp:
    out = os.path.join(tmp, "out")
    run = subprocess.run(["cpack", "--config", os.path.join(build, "CPackConfig.cmake"),
                          "-B", out], cwd=build, capture_output=True, text=True)
    debs = glob.glob(os.path.join(out, "*.deb"))
    check(run.returncode == 0 and len(debs) == 1, "cpack made one .deb: " +
          (run.stdout + run.stderr).strip().splitlines()[-1])
    deb = debs[0]
    info = subprocess.run(["dpkg-deb", "-f", deb, "Package", "Depends", "Architecture"],
                          capture_output=True, text=True, check=True).stdout
    fields = dict(line.split(": ", 1) for line in info.strip().splitlines())
    depends = [d.strip().split(" ")[0] for d in fields["Depends"].split(",")]
    for want in ("freecad-python3", "python3", "libocct-foundation-7.6",
                 "libocct-modeling-algorithms-7.6", "coinor-libcbc3"):
        check(want in depends, "depends on " + want)
    for name in set(depends):  # every name a real Debian package (installed here)
        known = subprocess.run(["dpkg-query", "-W", "-f=${Status}", name],
                               capture_output=True, text=True)
        check("install ok installed" in known.stdout, name + " is a Debian package")
    root = os.path.join(tmp, "root")
    subprocess.run(["dpkg", "-x", deb, root], check=True)
    mod = os.path.join(root, "usr", "share", "freecad", "Mod", "VoroHex")
    for f in ("Init.py", "InitGui.py", "package.xml", "VoroHex.py", "VoroHexObjects.py",
              "Gui/VoroHexGui/task_panel.py", "Resources/ui/HexMesh.ui", "bin/vorohex"):
        check(os.path.exists(os.path.join(mod, f)), "the package holds " + f)
    check(glob.glob(os.path.join(mod, "_VoroHexCore*.so")), "the package holds the module")
    home = os.path.join(tmp, "home")  # no user Mod folder: only the package's
    os.makedirs(home)
    code = ("import VoroHex, Part, sys\n"
            "print('FILE', VoroHex.__file__, VoroHex._core.__file__)\n"
            "r = VoroHex.mesh(Part.makeBox(3, 2, 1), size=0.5)\n"
            "print('MESH', r.ok, r.stats.hexes)\n")
    env = dict(os.environ, HOME=home)
    res = subprocess.run(["freecadcmd", "-c", code, "-M", mod], capture_output=True,
                         text=True, env=env, timeout=120)
    lines = {line.split(" ", 1)[0]: line for line in res.stdout.splitlines()
             if line.startswith(("FILE", "MESH"))}
    files = lines.get("FILE", "").split()[1:]
    check(len(files) == 2 and all(f.startswith(root) for f in files),
          "freecadcmd imports VoroHex from the package: {}".format(files))
    check(lines.get("MESH") == "MESH True 48", "and meshes a box with it: {}".format(
        lines.get("MESH") or res.stdout[-500:] + res.stderr[-500:]))
print("package_test: PASS")
