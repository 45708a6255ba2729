"""Ways to damage a result file, for the tests of its readers: each changes the
file ``path`` in place (the factories return such a function)."""

import h5py


def set_attr(name, value):
    """The attribute ``name`` (of the root, or ``group/attr``) set to ``value``."""
    def damage(path):
        where, _, attr = name.rpartition("/")
        with h5py.File(path, "r+") as f:
            f[where or "/"].attrs[attr] = value
    return damage


def delete_attr(name):
    """The attribute ``name`` (of the root, or ``group/attr``) deleted."""
    def damage(path):
        where, _, attr = name.rpartition("/")
        with h5py.File(path, "r+") as f:
            del f[where or "/"].attrs[attr]
    return damage


def replace_dataset(name, values):
    """The object ``name`` deleted and, unless ``values`` is None, a dataset of ``values`` in its place."""
    def damage(path):
        with h5py.File(path, "r+") as f:
            del f[name]
            if values is not None:
                f[name] = values
    return damage


def truncate(path):
    """The second half of the file cut off."""
    data = path.read_bytes()
    path.write_bytes(data[:len(data) // 2])


def text(path):
    """A text file in its place."""
    path.write_text("length_m,drag_fe_N\n400,1\n")


def empty(path):
    """An empty file in its place."""
    path.write_bytes(b"")


def foreign(path):
    """Another program's HDF5 file in its place."""
    path.unlink()
    with h5py.File(path, "w") as f:
        f["data"] = [1.0]
