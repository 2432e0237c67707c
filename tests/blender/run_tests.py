"""Runs the add-on suite (test_addon.py, test_maps.py, then test_pair_maps.py) in whatever Blender imports this file.

    blender -b --factory-startup --python-exit-code 1 -P tests/blender/run_tests.py
    .venv-bpy/bin/python tests/blender/run_tests.py          # bpy module from PyPI

Each test starts from an empty scene with the add-on registered. Prints one line
per test and "N passed, M failed"; exits 1 if anything failed.
CMAPS_BLENDER_TESTS=<substring> runs only the tests whose name contains it.
"""
import faulthandler
import os
import pathlib
import sys
import time
import traceback

HERE = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(HERE.parents[1] / "addon"), str(HERE)]
faulthandler.dump_traceback_later(900, exit=True)  # a hung test must not hang the whole test command

import bpy  # noqa: E402

import test_addon  # noqa: E402
import test_maps  # noqa: E402
import test_pair_maps  # noqa: E402


def main():
    import consistent_maps
    selected = os.environ.get("CMAPS_BLENDER_TESTS", "")
    tests = [(name, fn) for module in (test_addon, test_maps, test_pair_maps) for name, fn in vars(module).items()
             if name.startswith("test_") and callable(fn) and selected in name and fn.__module__ == module.__name__]
    where = "bpy module" if not bpy.app.binary_path or "site-packages" in bpy.app.binary_path else "Blender"
    print(f"== Consistent Maps add-on tests in {where} {bpy.app.version_string}, {len(tests)} tests")
    consistent_maps.register()
    failed = []
    start = time.time()
    for name, fn in tests:
        t0 = time.time()
        try:
            test_addon.reset()
            fn()
            print(f"PASS {name} ({time.time() - t0:.1f} s)", flush=True)
        except Exception:
            traceback.print_exc()
            print(f"FAIL {name} ({time.time() - t0:.1f} s)", flush=True)
            failed.append(name)
    test_addon.reset()
    consistent_maps.unregister()
    print(f"{len(tests) - len(failed)} passed, {len(failed)} failed "
          f"(Blender {bpy.app.version_string}, {time.time() - start:.0f} s)"
          + (f": {', '.join(failed)}" if failed else ""), flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    code = main()
    sys.stdout.flush()
    os._exit(code)  # Blender's own exit path would ignore the code; os._exit keeps it
