"""An error injected into a kernel of the LAMMPS bridge, for the tests of its error handling (imported by
test_lammps.py and lammps_rank_error.py)."""


def failing_after(calls, kernel):
    """``kernel``, raising MemoryError("injected") from its call number calls + 1 on."""
    count = [0]

    def failing(*args):
        count[0] += 1
        if count[0] > calls:
            raise MemoryError("injected")
        return kernel(*args)

    return failing
