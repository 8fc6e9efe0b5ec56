"""What the program-level fuzz drivers (run_hostile_vdbs.py, run_hostile_json.py) share: the
limits a run of the nimbus program gets, and how its end is named."""
import resource
import signal


def limits(mem_mb, cpu_s):
    """A preexec_fn setting soft limits only: nimbus may start a reader that sets limits of its own,
    and one above a hard limit inherited from here would fail (EPERM) for reasons that are not the
    input's. RLIMIT_CPU (SIGXCPU) stops a run spinning however loaded the machine; no core files."""
    def soft(which, value):
        resource.setrlimit(which, (value, resource.getrlimit(which)[1]))

    def apply():
        if mem_mb > 0:
            soft(resource.RLIMIT_AS, mem_mb << 20)
        if cpu_s > 0:
            soft(resource.RLIMIT_CPU, cpu_s)
        soft(resource.RLIMIT_CORE, 0)
    return apply


def outcome(rc, timed_out):
    """'hang', 'signal SIGSEGV', 'signal 9' (a shell-style 128 + N code) or 'exit N'."""
    if timed_out:
        return "hang"
    if rc < 0:
        return "signal %s" % signal.Signals(-rc).name
    if rc > 128 and rc - 128 < 65:
        return "signal %d" % (rc - 128)
    return "exit %d" % rc
