"""Where the project's programs are: the planner CLI and the cost table generator.

An explicit path wins; otherwise they are looked up in the build directory named by
--build-dir or $HV_BUILD_DIR (what ctest sets). A missing program is an error that says
where it was looked for, never a silent substitute.
"""

import os

PLANNER = os.path.join("planner", "harvest-plan")
COSTGEN = os.path.join("tools", "costgen")


class MissingProgram(RuntimeError):
    pass


def build_dir(explicit=None):
    return explicit or os.environ.get("HV_BUILD_DIR")


def find(relpath, explicit_path=None, explicit_build_dir=None):
    """Absolute path of an executable, or MissingProgram naming every place tried."""
    if explicit_path:
        tried = [explicit_path]
    else:
        bdir = build_dir(explicit_build_dir)
        if not bdir:
            raise MissingProgram(
                f"{relpath}: no build directory (give --build-dir or set HV_BUILD_DIR)"
            )
        tried = [os.path.join(bdir, relpath)]
    for p in tried:
        if os.path.isfile(p) and os.access(p, os.X_OK):
            return os.path.abspath(p)
    raise MissingProgram(f"{relpath}: not built: no executable at {', '.join(tried)}")


def build_info(program):
    """CMAKE_BUILD_TYPE and HV_SANITIZE of the build a program came from (runtimes depend
    on both); empty when the program is not in a CMake build tree."""
    bdir = os.path.dirname(os.path.dirname(os.path.realpath(program)))
    cache = os.path.join(bdir, "CMakeCache.txt")
    info = {}
    if not os.path.isfile(cache):
        return info
    with open(cache, encoding="utf-8", errors="replace") as f:
        for line in f:
            for key in ("CMAKE_BUILD_TYPE", "HV_SANITIZE"):
                if line.startswith(key + ":"):
                    info[key] = line.split("=", 1)[1].strip()
    return info
