"""roslaunch and rosrun find ``arm1 NAME`` by walking the whole package folder: a second file
of that name anywhere in it (a test robot's gazebo.launch, say) makes ``roslaunch arm1
gazebo.launch`` stop with "multiple files named [gazebo.launch] in package [arm1]"."""

import collections
import os

from helpers import REPO_ROOT

# What make setup links into .ws/src/arm1 leaves out (Makefile, link-package).
NOT_IN_PACKAGE = {'tools'}


def test_no_launch_file_or_executable_name_is_in_the_package_twice() -> None:
    seen = collections.defaultdict(list)
    for root, dirs, files in os.walk(REPO_ROOT):
        rel = os.path.relpath(root, REPO_ROOT)
        if rel == '.':
            dirs[:] = [d for d in dirs if d not in NOT_IN_PACKAGE]
        dirs[:] = [d for d in dirs if not d.startswith('.') and d != '__pycache__']
        for name in files:
            path = os.path.join(root, name)
            if name.endswith(('.launch', '.test')) or os.access(path, os.X_OK):
                seen[name].append(os.path.relpath(path, REPO_ROOT))
    assert {n: p for n, p in seen.items() if len(p) > 1} == {}
