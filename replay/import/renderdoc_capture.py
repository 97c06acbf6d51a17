"""Captures one frame of a program that knows nothing of RenderDoc, as RenderDoc's UI does: launch it
with RenderDoc injected (into its children too), connect through target control, wait until it
uses a graphics API RenderDoc can capture, run the user's commands, trigger, wait for the file.

  renderdoc_capture.py --out FILE.rdc --result RESULT.json [--after-frames N] [--timeout S]
                       [--after-register CMD] [--after-trigger CMD] -- PROGRAM [ARGS...]

Run by `aoreplay renderdoc-capture` (replay/import/renderdoc_capture.h), which embeds it. RESULT
receives {"captured": {...}} or, for what the user can act on, {"error": {"field", "message"}}.
A wrapper script that execs its program, or starts it as a child, is followed to it. The program
is stopped once the capture is written or the attempt fails.
"""
import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import time


class CaptureFailure(Exception):
    def __init__(self, field, message):
        super().__init__(message)
        self.field = field


def parse_arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", required=True)
    p.add_argument("--result", required=True)
    p.add_argument("--after-frames", type=int, default=5)
    p.add_argument("--timeout", type=float, default=60.0)
    p.add_argument("--after-register", default="")
    p.add_argument("--after-trigger", default="")
    p.add_argument("--renderdoc-python", default="")
    p.add_argument("program", nargs=argparse.REMAINDER)
    args = p.parse_args()
    if args.program[:1] == ["--"]:
        args.program = args.program[1:]
    return args


def import_renderdoc(directory):
    if directory:
        sys.path.insert(0, directory)
    try:
        import renderdoc
    except ImportError as e:
        raise CaptureFailure("--renderdoc-python", "cannot import RenderDoc's Python module (%s); install Debian's "
                             "python3-renderdoc (apt-get install python3-renderdoc)" % e)
    return renderdoc


def connect(rd, ident, deadline):
    while time.time() < deadline:
        control = rd.CreateTargetControl("", ident, "aoreplay", True)
        if control is not None and control.Connected():
            return control
        time.sleep(0.05)
    return None


def run_user_command(command, field, program):
    if not command:
        return
    done = subprocess.run(command, shell=True)
    if done.returncode != 0:
        raise CaptureFailure(field, "%r exited with %d while capturing %s" % (command, done.returncode, program))


class Target:
    """The connection to the process that uses the graphics API: the launched one, or the program a
    wrapper script starts (a child, followed when RenderDoc announces it) or execs (the same ident
    again after a disconnect)."""

    def __init__(self, rd, ident, program, deadline):
        self.rd, self.program, self.deadline = rd, program, deadline
        self.ident = ident
        self.control = connect(rd, ident, deadline)
        if self.control is None:
            raise CaptureFailure("", "cannot connect to RenderDoc in %s (target control)" % program)
        self.launched = self.control.GetPID()
        self.pids = {self.launched}
        self.next_look = 0.0

    def switch_to(self, ident, patience):
        control = connect(self.rd, ident, min(self.deadline, time.time() + patience))
        if control is None:
            return False
        if not descends_from(control.GetPID(), self.launched):
            # Another RenderDoc-injected program took the port: a concurrent capture's, never ours.
            control.Shutdown()
            return False
        self.control.Shutdown()
        self.control, self.ident = control, ident
        self.pids.add(control.GetPID())
        return True

    def descendants(self, include_current=False):
        """Target-control idents of the launched process and its descendants (RenderDoc 1.24
        announces no child of a wrapper script that waits for it): found by enumerating the
        targets, each asked for its PID without taking it from a client it has."""
        found, ident = [], self.rd.EnumerateRemoteTargets("", 0)
        while ident and len(found) < 64:
            if include_current or ident != self.ident:
                control = self.rd.CreateTargetControl("", ident, "aoreplay", False)
                if control is not None:
                    if control.Connected() and descends_from(control.GetPID(), self.launched):
                        found.append(ident)
                    control.Shutdown()
            ident = self.rd.EnumerateRemoteTargets("", ident)
        return found

    def reconnect(self, patience):
        """After a disconnect (a wrapper that execs the program): the same process again, at its old
        port or, when another program took that one meanwhile (a concurrent capture), at whichever
        port it got."""
        until = min(self.deadline, time.time() + patience)
        while time.time() < until:
            if any(self.switch_to(i, 0.5) for i in self.descendants(include_current=True)):
                return True
            time.sleep(0.05)
        return False

    def follow_child(self):
        if time.time() < self.next_look:
            return
        self.next_look = time.time() + 0.5
        for ident in self.descendants():
            if self.switch_to(ident, 2.0):
                return

    def next_message(self, wanted):
        """Messages until one of type `wanted`, following children and execs on the way."""
        t = self.rd.TargetControlMessageType
        while time.time() < self.deadline:
            message = self.control.ReceiveMessage(None)
            if message.type == t.NewChild and wanted == t.RegisterAPI:
                self.pids.add(message.newChild.processId)
                self.switch_to(message.newChild.ident, 5.0)
            elif message.type == t.Disconnected:
                if not self.reconnect(2.0):
                    raise CaptureFailure("", "%s exited before %s" % (self.program, WAITING_FOR[wanted]))
            elif message.type == wanted:
                return message
            elif wanted == t.RegisterAPI:
                self.follow_child()
        raise CaptureFailure("--timeout", "%s did not %s within the time limit" % (self.program, WAITING_FOR_VERB[wanted]))


def descends_from(pid, ancestor):
    """Whether `pid` is `ancestor` or one of its descendants (parents read from /proc)."""
    for _ in range(64):
        if pid == ancestor:
            return True
        try:
            with open("/proc/%d/stat" % pid) as f:
                pid = int(f.read().rsplit(")", 1)[1].split()[1])
        except (OSError, ValueError, IndexError):
            return False
        if pid <= 1:
            return False
    return False


WAITING_FOR = {}
WAITING_FOR_VERB = {}


def stop(pids):
    """Ends the captured program and what it started (children of this process are reaped)."""
    for pid in pids:
        try:
            os.kill(pid, signal.SIGTERM)
        except (ProcessLookupError, PermissionError):
            pass
    for pid in pids:
        for _ in range(200):
            try:
                if os.waitpid(pid, os.WNOHANG)[0] == pid:
                    break
            except ChildProcessError:
                try:
                    os.kill(pid, 0)
                except ProcessLookupError:
                    break
            time.sleep(0.01)
        else:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass


def capture(rd, args):
    t = rd.TargetControlMessageType
    WAITING_FOR.update({t.RegisterAPI: "using a graphics API RenderDoc can capture",
                        t.NewCapture: "the capture was written (a crash while RenderDoc captured? a later frame may "
                                      "work: --after-frames 300)"})
    WAITING_FOR_VERB.update({t.RegisterAPI: "use a graphics API RenderDoc can capture (is it presenting frames?)",
                             t.NewCapture: "present the frame the capture was triggered for (--after-trigger can "
                                           "make it draw: resize its window, press a key)"})
    deadline = time.time() + args.timeout
    program = shutil.which(args.program[0]) or args.program[0]
    if not os.path.isfile(program) or not os.access(program, os.X_OK):
        raise CaptureFailure("PROGRAM", "%s is not an executable program" % args.program[0])
    work = os.path.abspath(args.out) + ".parts"
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    options = rd.GetDefaultCaptureOptions()
    options.hookIntoChildren = True  # a wrapper script's program is its child, or its own exec
    launched = rd.ExecuteAndInject(program, os.getcwd(), " ".join(args.program[1:]), [],
                                   os.path.join(work, "capture"), options, False)
    if launched.result.code != rd.ResultCode.Succeeded:
        raise CaptureFailure("PROGRAM", "RenderDoc cannot launch %s: %s" % (program, launched.result.Message()))
    target = Target(rd, launched.ident, program, deadline)
    try:
        api = target.next_message(t.RegisterAPI).apiUse
        if not api.supported:
            raise CaptureFailure("PROGRAM", "RenderDoc cannot capture %s's %s: %s"
                                 % (program, api.name, api.supportMessage or "(RenderDoc gave no reason)"))
        while not api.presenting:  # a trigger before the first present was lost (Qt's Vulkan examples)
            api = target.next_message(t.RegisterAPI).apiUse
        run_user_command(args.after_register, "--after-register", program)
        time.sleep(args.after_frames / 60.0)
        target.control.TriggerCapture(1)
        run_user_command(args.after_trigger, "--after-trigger", program)
        captured = target.next_message(t.NewCapture).newCapture
        shutil.move(captured.path, args.out)
        return {"file": args.out, "frame": captured.frameNumber, "api": captured.api, "program": program,
                "target": target.control.GetTarget(), "pid": target.control.GetPID()}
    finally:
        target.control.Shutdown()
        stop(target.pids)
        shutil.rmtree(work, ignore_errors=True)


def main():
    args = parse_arguments()
    result = {}
    try:
        if not args.program:
            raise CaptureFailure("PROGRAM", "no program to capture (give it after --)")
        rd = import_renderdoc(args.renderdoc_python)
        result["captured"] = capture(rd, args)
    except CaptureFailure as e:
        result["error"] = {"field": e.field, "message": str(e)}
    with open(args.result, "w") as f:
        json.dump(result, f)


if __name__ == "__main__":
    main()
    # RenderDoc's threads can keep an ordinary interpreter exit waiting (as renderdoc_dump.py).
    sys.stdout.flush()
    os._exit(0)
