"""A stand-in for the ``blender`` executable on test farm workers, built on the bpy module.

There is no Blender binary on the test machines, only Blender as a Python module. Flamenco's
``blender-render`` command runs ``{blender} {blenderArgs} [file.blend] ARGS``; this shim takes the
same command line and handles it the way Blender does, argument by argument, in order:

- ``-b``/``--background``, ``-y``/``--enable-autoexec``: accepted (the module is always in the
  background);
- ``file.blend``: opened;
- ``--python-exit-code N``: exit with N when a later Python expression or script raises;
- ``--python-expr CODE`` / ``--python FILE`` (``-P``): run, with ``sys.argv`` as Blender's (so a script
  reads its own arguments after ``--``);
- ``--``: the end of Blender's arguments.

Anything else is refused with a message naming the argument, rather than ignored.

For the failure test only: when ``PRISM_SHIM_FAIL_ONCE`` names a file whose text is an output file
name, the first run writing that output removes the file and exits with status 1, as a crashed
render would. Flamenco then gives the task to another worker.
"""

from __future__ import annotations

import os
import sys
import traceback
from pathlib import Path

SHIM_NAME = "blender shim"


class ShimError(Exception):
    """A command line the shim (and Blender) cannot run."""


def fail_once_if_asked(arguments: list[str]) -> None:
    """Exit 1 once for the output named in ``$PRISM_SHIM_FAIL_ONCE`` (see the module docstring)."""
    marker = os.environ.get("PRISM_SHIM_FAIL_ONCE")
    if not marker or "--output" not in arguments:
        return
    output = arguments[arguments.index("--output") + 1]
    try:
        wanted = Path(marker).read_text(encoding="utf-8").strip()
    except FileNotFoundError:
        return
    if Path(output).name != wanted:
        return
    try:
        os.unlink(marker)  # only one worker wins the unlink, so only one run fails
    except FileNotFoundError:
        return
    print(f"{SHIM_NAME}: failing on purpose while writing {output} ($PRISM_SHIM_FAIL_ONCE)", file=sys.stderr)
    exit_now(1)


def run_python(kind: str, action, exit_code: int) -> None:
    """Run a ``--python-expr``/``--python`` action; on an exception behave as Blender does."""
    try:
        action()
    except SystemExit:
        raise
    except Exception:  # noqa: BLE001 - Blender prints the traceback and goes on unless told otherwise
        traceback.print_exc()
        if exit_code:
            print(f"{SHIM_NAME}: {kind} raised: exiting with --python-exit-code {exit_code}", file=sys.stderr)
            exit_now(exit_code)


def run_script(script: str, argv: list[str]) -> None:
    """Run ``script`` as Blender's ``-P`` does: as ``__main__``, with ``sys.argv`` the whole command
    line, program first (a script tells it runs inside Blender by ``sys.argv[0]`` not being itself)."""
    path = Path(script)
    if not path.is_file():
        raise ShimError(f"cannot read --python script '{script}': no such file")
    sys.argv = [sys.argv[0], *argv]
    code = compile(path.read_text(encoding="utf-8"), str(path), "exec")
    exec(code, {"__name__": "__main__", "__file__": str(path)})


def run(argv: list[str]) -> int:
    """Handle ``argv`` (without the program name) in order, as Blender's command line does."""
    import bpy

    blender_args, script_args = (argv[: argv.index("--")], argv[argv.index("--") :]) if "--" in argv else (argv, [])
    fail_once_if_asked(script_args)
    exit_code = 0
    position = 0

    def value(option: str) -> str:
        nonlocal position
        if position + 1 >= len(blender_args):
            raise ShimError(f"{option} needs a value")
        position += 1
        return blender_args[position]

    while position < len(blender_args):
        argument = blender_args[position]
        if argument in ("-b", "--background", "-y", "--enable-autoexec"):
            pass
        elif argument == "--python-exit-code":
            exit_code = int(value(argument))
        elif argument == "--python-expr":
            code = value(argument)
            run_python("--python-expr", lambda: exec(compile(code, "<--python-expr>", "exec"), {"bpy": bpy}), exit_code)
        elif argument in ("-P", "--python"):
            script = value(argument)
            run_python("--python", lambda: run_script(script, argv), exit_code)
        elif argument.endswith(".blend") and not argument.startswith("-"):
            if not Path(argument).is_file():
                raise ShimError(f"cannot read file '{argument}': no such file")
            bpy.ops.wm.open_mainfile(filepath=str(Path(argument).resolve()))
        else:
            raise ShimError(f"argument '{argument}' is not handled by the test shim (extend tests/farm/blender_shim.py)")
        position += 1
    return 0


def exit_now(status: int) -> None:
    """Leave at once, as Blender's batch scripts do (render.py's ``exit_now``)."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
    from render import exit_now as leave

    leave(status)


if __name__ == "__main__":
    try:
        exit_now(run(sys.argv[1:]))
    except ShimError as error:
        print(f"{SHIM_NAME}: error: {error}", file=sys.stderr)
        exit_now(2)
