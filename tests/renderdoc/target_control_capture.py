#!/usr/bin/env python3
"""Captures one frame of a program that knows nothing of RenderDoc, the way RenderDoc's UI does:
launch it with RenderDoc injected, connect through target control, trigger a capture, wait for it.

  target_control_capture.py --out FILE.rdc [--after-frames N] [--timeout S] -- PROGRAM [ARGS...]

Used by the vkcube import test (vkcube under xvfb-run). Needs Debian's python3-renderdoc and
librenderdoc. The program is stopped once the capture is written.
"""
import argparse
import os
import shutil
import signal
import sys
import time

import renderdoc as rd


def parse_arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", required=True)
    p.add_argument("--after-frames", type=int, default=5, help="let the program present this many frames first")
    p.add_argument("--timeout", type=float, default=60.0)
    p.add_argument("program", nargs=argparse.REMAINDER)
    args = p.parse_args()
    if args.program[:1] == ["--"]:
        args.program = args.program[1:]
    if not args.program:
        p.error("no program to capture")
    return args


def connect(ident, deadline):
    while time.time() < deadline:
        control = rd.CreateTargetControl("", ident, "aoreplay-test", True)
        if control is not None and control.Connected():
            return control
        time.sleep(0.05)
    sys.exit("target_control_capture: cannot connect to the program's RenderDoc target control")


def wait_for(control, wanted, deadline):
    while time.time() < deadline:
        message = control.ReceiveMessage(None)
        if message.type == rd.TargetControlMessageType.Disconnected:
            sys.exit("target_control_capture: the program went away before the capture")
        if message.type == wanted:
            return message
    sys.exit("target_control_capture: timed out waiting for %s" % wanted)


def stop(pid):
    """Ends the captured program and reaps it (it is this process's child)."""
    try:
        os.kill(pid, signal.SIGTERM)
        for _ in range(200):
            if os.waitpid(pid, os.WNOHANG)[0] == pid:
                return
            time.sleep(0.01)
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
    except (ProcessLookupError, ChildProcessError):
        pass


def main():
    args = parse_arguments()
    deadline = time.time() + args.timeout
    work = os.path.abspath(args.out) + ".parts"
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    program = shutil.which(args.program[0]) or args.program[0]
    launched = rd.ExecuteAndInject(program, os.getcwd(), " ".join(args.program[1:]), [],
                                   os.path.join(work, "capture"), rd.GetDefaultCaptureOptions(), False)
    if launched.result.code != rd.ResultCode.Succeeded:
        sys.exit("target_control_capture: cannot launch %s: %s" % (program, launched.result.Message()))
    control = connect(launched.ident, deadline)
    pid = control.GetPID()
    try:
        wait_for(control, rd.TargetControlMessageType.RegisterAPI, deadline)
        time.sleep(args.after_frames / 60.0)
        control.TriggerCapture(1)
        captured = wait_for(control, rd.TargetControlMessageType.NewCapture, deadline).newCapture
        shutil.move(captured.path, args.out)
        print("captured frame %d of %s (%s) into %s" % (captured.frameNumber, program, captured.api, args.out))
    finally:
        control.Shutdown()
        if pid:
            stop(pid)
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
    # As renderdoc_dump.py: RenderDoc's threads can keep an ordinary interpreter exit waiting.
    sys.stdout.flush()
    os._exit(0)
