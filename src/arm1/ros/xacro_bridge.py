"""Run PyPI's xacro (2.x) with ``$(find pkg)`` resolved the ROS 1 way.

PyPI's xacro resolves ``$(find pkg)`` through ROS 2's ament index, which a
ROS 1 (catkin / Debian) system does not have.  This module replaces xacro's
find function with one that asks rospkg (``ROS_PACKAGE_PATH``), so
``xacro '$(find arm1)/urdf/arm1.urdf.xacro'`` works as it did on ROS 1.

Usable without ROS: when rospkg is missing or does not know the package,
``arm1`` itself still resolves to this source tree.
"""

import os
import sys

from ..paths import repo_root

_rospack = None


def _not_found(pkg):
    try:
        from xacro.substitution_args import SubstitutionException
    except ImportError:  # pragma: no cover - xacro missing entirely
        SubstitutionException = LookupError
    return SubstitutionException("package '%s' not found on ROS_PACKAGE_PATH" % pkg)


def find_package(pkg):
    """Return the directory of ROS package ``pkg`` (what ``rospack find`` prints)."""
    global _rospack
    try:
        import rospkg
    except ImportError:
        rospkg = None
    if rospkg is not None:
        try:
            if _rospack is None:
                _rospack = rospkg.RosPack()
            return _rospack.get_path(pkg)
        except rospkg.ResourceNotFound:
            pass
    if pkg == 'arm1' and os.path.isfile(os.path.join(repo_root(), 'package.xml')):
        return repo_root()
    raise _not_found(pkg)


def install():
    """Make xacro's ``$(find pkg)`` (both the substitution arg and the one
    usable inside ``$(eval ...)``) resolve through :func:`find_package`."""
    from xacro import substitution_args
    substitution_args._eval_find = find_package
    substitution_args._eval_dict['find'] = find_package


def expand(path, mappings=None):
    """Expand the xacro file ``path`` in-process and return the XML text.

    ``mappings`` is a dict of xacro arguments (what ``name:=value`` gives on
    the command line)."""
    import xacro
    install()
    doc = xacro.process_file(path, mappings=dict(mappings or {}))
    return doc.toprettyxml(indent='  ')


def main(argv=None):
    """Command line entry point, same options as ``xacro``."""
    import xacro
    install()
    if argv is not None:
        sys.argv = [sys.argv[0]] + list(argv)
    return xacro.main()


if __name__ == '__main__':
    main()
