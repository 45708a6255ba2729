"""fem_tether.core.threads: the cores of a node shared among its MPI ranks' linear-algebra threads."""

from fem_tether.core.threads import THREAD_VARIABLES, share_cores_among_ranks


def test_two_ranks_on_two_cores_run_one_thread_each():
    environ = {"MPI_LOCALNRANKS": "2"}
    assert share_cores_among_ranks(environ, cores=2) == 1
    assert all(environ[name] == "1" for name in THREAD_VARIABLES)


def test_cores_are_divided_among_the_ranks_and_a_set_count_is_kept():
    environ = {"OMPI_COMM_WORLD_LOCAL_SIZE": "3", "OMP_NUM_THREADS": "4"}
    assert share_cores_among_ranks(environ, cores=8) == 2
    assert environ["OPENBLAS_NUM_THREADS"] == "2" and environ["OMP_NUM_THREADS"] == "4"


def test_one_rank_or_no_launcher_sets_nothing():
    for environ in ({}, {"MPI_LOCALNRANKS": "1"}, {"MPI_LOCALNRANKS": "x"}):
        before = dict(environ)
        assert share_cores_among_ranks(environ, cores=2) is None and environ == before


def test_more_ranks_than_cores_still_run_one_thread():
    environ = {"MPI_LOCALNRANKS": "4"}
    assert share_cores_among_ranks(environ, cores=2) == 1
