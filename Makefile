# Set-up, build and run targets for arm1 (ROS 1 from Debian 12's own packages).
#
#   make setup   apt packages, .ws/venv (pip pins in requirements.txt) and the
#                catkin workspace .ws/ (.ws/src/arm1: links to this repo), built. Idempotent;
#                stamp files under .ws/stamps make a second run take ~0.05 s.
#   make build   catkin_make of .ws (always runs)
#   make demo | test | bench   run inside the sourced workspace (tools/ws-run), ROS on loopback only
#   make soak    robot_spawn.launch under simple_mover for SOAK_MINUTES (10); not in make test
#   make test-stress  make test STRESS_RUNS (3) times in a fresh clone with one core kept busy,
#                then again with two (STRESS_BUSY="1 2"; stress-ng, installed by this target
#                only): tools/test-stress
#   make clean   remove .ws
#
# Runs as root (apt-get); elsewhere apt-get is run through sudo.

SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := setup

ROOT    := $(patsubst %/,%,$(dir $(abspath $(lastword $(MAKEFILE_LIST)))))
WS      := $(ROOT)/.ws
VENV    := $(WS)/venv
STAMPS  := $(WS)/stamps
SYS_PY  := /usr/bin/python3
VENV_PY := $(VENV)/bin/python3
WS_SHELL := $(ROOT)/tools/ws-run
PKG_LINK := $(WS)/src/arm1

SUDO := $(if $(filter 0,$(shell id -u)),,sudo)

# What robot packages' CMakeLists find_package besides Gazebo and ros_control (whose
# stand-ins tools/make_compat_packages.py writes): Debian's -dev packages (docs/building.md;
# 233 packages, 48 MB: 5 s download, 35 s install measured here).
ROBOT_BUILD_DEPENDS := \
  librobot-state-publisher-dev librviz-dev libtf2-ros-dev libtf-dev libtf2-geometry-msgs-dev \
  libtf2-eigen-dev libtf2-kdl-dev libtf-conversions-dev libkdl-parser-dev liborocos-kdl-dev \
  libactionlib-dev libinteractive-markers-dev libvisualization-msgs-dev libangles-dev \
  libimage-transport-dev libcv-bridge-dev libimage-geometry-dev libcamera-info-manager-dev \
  liblaser-geometry-dev libmessage-filters-dev librosbag-dev libnodelet-dev \
  libresource-retriever-dev libdiagnostic-updater-dev libeigen3-dev

# The everyday nodes robot launch files start besides the simulator (docs/building.md):
# tf2_ros's and tf's static_transform_publisher, topic_tools' relay/throttle/mux, image_view,
# image_transport's republish (23 packages, 3 MB: about 75 s to install measured here under load).
LAUNCH_NODE_PACKAGES := \
  tf2-tools tf-tools topic-tools python3-topic-tools ros-image-view libimage-view-dev \
  image-transport-tools

APT_PACKAGES := \
  python3-rospy python3-roslaunch python3-rostest librostest-dev python3-rosunit rosbash \
  catkin rosout ros-robot-state-publisher joint-state-publisher \
  python3-std-msgs python3-sensor-msgs python3-std-srvs python3-geometry-msgs \
  python3-rosgraph-msgs python3-trajectory-msgs python3-actionlib-msgs python3-actionlib \
  ros-std-msgs libstd-msgs-dev ros-geometry-msgs libgeometry-msgs-dev \
  ros-sensor-msgs libsensor-msgs-dev ros-std-srvs libstd-srvs-dev \
  python3-shape-msgs ros-shape-msgs libshape-msgs-dev \
  ros-rosgraph-msgs libros-rosgraph-msgs-dev \
  ros-trajectory-msgs libtrajectory-msgs-dev ros-actionlib-msgs libactionlib-msgs-dev \
  python3-nav-msgs ros-nav-msgs libnav-msgs-dev python3-tf2-msgs ros-tf2-msgs \
  python3-dynamic-reconfigure libdynamic-reconfigure-config-init-mutex-dev \
  ros-message-generation ros-message-runtime \
  python3-rosservice python3-rostopic python3-rosparam python3-rosnode \
  python3-rosmsg python3-rosbag rospack-tools python3-rosmaster python3-rospkg \
  python3-catkin-pkg libroscpp-dev liburdf-dev \
  python3-venv python3-pip python3-numpy python3-yaml python3-psutil python3-defusedxml python3-tqdm python3-pil \
  cmake make g++ xvfb \
  rviz joint-state-publisher-gui libgl1-mesa-dri libglx-mesa0 \
  $(LAUNCH_NODE_PACKAGES) \
  libegl1 libegl-mesa0 libgl1 libgles2 chromium python3-websocket \
  $(ROBOT_BUILD_DEPENDS)

# A change to any of these rebuilds the workspace (python modules under
# src/_arm1sim need no rebuild: the devel space imports them from src/).
BUILD_INPUTS := $(addprefix $(ROOT)/,package.xml CMakeLists.txt setup.py) \
  $(wildcard $(ROOT)/msg/*.msg $(ROOT)/srv/*.srv $(ROOT)/env-hooks/*) \
  $(filter-out %/__pycache__,$(wildcard $(ROOT)/scripts/*)) \
  $(wildcard $(ROOT)/src/*/__init__.py) $(ROOT)/tools/make_compat_packages.py \
  $(wildcard $(ROOT)/tools/compat_*.py) \
  $(wildcard $(ROOT)/tools/compat_msgs/*/*/*) $(wildcard $(ROOT)/tools/compat_cfg/*/*)

.PHONY: setup venv build demo web-picture test test-stress lint bench soak clean link-package

# A stamp is only trusted while what it stands for is still there.
ifeq ($(wildcard $(VENV_PY)),)
.PHONY: $(STAMPS)/venv
endif
ifeq ($(wildcard $(WS)/devel/setup.bash),)
.PHONY: $(STAMPS)/build
endif

setup: $(STAMPS)/build link-package

# Only the Debian packages and .ws/venv, for a workspace of your own (~/catkin_ws): a
# catkin workspace inside the package would give rosrun two copies of every node.
venv: $(STAMPS)/venv

# a. Debian packages: dpkg-query first, so a re-run does no apt work at all.
#    Another apt holding the lock (unattended upgrades) is waited for, up to APT_LOCK_TIMEOUT s:
#    apt's own DPkg::Lock::Timeout for install; update (lists lock, which that option does
#    not cover in apt 2.6) is retried while apt says the lock is held.
APT_LOCK_TIMEOUT ?= 600
$(STAMPS)/apt: $(ROOT)/Makefile
	@mkdir -p $(STAMPS)
	@missing=""; \
	for p in $(APT_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' "$$p" 2>/dev/null | grep -q 'ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "setup: apt-get install$$missing"; \
	  echo "setup: if another apt holds the package lock (unattended upgrades on a fresh machine), this waits for it, up to $(APT_LOCK_TIMEOUT) s"; \
	  deadline=$$(( $$(date +%s) + $(APT_LOCK_TIMEOUT) )); said=""; \
	  until $(SUDO) env LC_ALL=C DEBIAN_FRONTEND=noninteractive apt-get update -q 2>$(STAMPS)/apt-update.err; do \
	    if grep -q 'Could not get lock' $(STAMPS)/apt-update.err && [ $$(date +%s) -lt $$deadline ]; then \
	      [ -n "$$said" ] || echo "setup: waiting for the apt lists lock: $$(grep -m1 'Could not get lock' $(STAMPS)/apt-update.err)"; \
	      said=1; sleep 5; \
	    else cat $(STAMPS)/apt-update.err >&2; exit 1; fi; \
	  done; \
	  cat $(STAMPS)/apt-update.err >&2; rm -f $(STAMPS)/apt-update.err; \
	  $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=$(APT_LOCK_TIMEOUT) \
	    install -y -q --no-install-recommends $$missing; \
	else \
	  echo "setup: Debian packages already installed"; \
	fi
	@touch $@

# b. venv that sees Debian's ROS (system site-packages) plus the pip pins.
$(STAMPS)/venv: $(ROOT)/requirements.txt $(STAMPS)/apt
	@if [ ! -x $(VENV_PY) ] || ! $(VENV_PY) -c 'import sys' 2>/dev/null; then \
	  rm -rf $(VENV); \
	  echo "setup: creating $(VENV)"; \
	  $(SYS_PY) -m venv --system-site-packages $(VENV); \
	fi
	$(VENV_PY) -m pip install -q --disable-pip-version-check -r $(ROOT)/requirements.txt
	@touch $@

# c. catkin workspace .ws: .ws/src/arm1 stands for this repo. It is a real
#    directory of symlinks to the repo's top-level entries (not one symlink
#    to the repo root), leaving out dot-entries (.ws, .git, ...) and tools/:
#    the package dir that rospack reports must not contain .ws itself, or
#    `rosrun arm1 NODE` (find -L over the package dir) loops through
#    .ws/src/arm1/.ws/... and finds the node's name many times over (devel
#    relays, build dir, venv bin, tools/bin/xacro) and stops to ask which.
#    Re-synced on every `make setup` (a few ms), so new top-level dirs show up.
link-package:
	@if [ -L $(PKG_LINK) ]; then rm -f $(PKG_LINK); fi
	@mkdir -p $(PKG_LINK)
	@cd $(PKG_LINK) && \
	for e in $(ROOT)/*; do \
	  n=$${e##*/}; \
	  case "$$n" in tools|'*') continue ;; esac; \
	  [ "$$(readlink "$$n" 2>/dev/null)" = "../../../$$n" ] || ln -sfn "../../../$$n" "$$n"; \
	done; \
	for l in *; do \
	  if [ -L "$$l" ] && [ ! -e "$$l" ]; then rm -f "$$l"; fi; \
	done
	@# gazebo_ros, controller_manager and xacro stand-ins, and gazebo_msgs, control_msgs and
	@# controller_manager_msgs (from tools/compat_msgs): packages of their own beside arm1.
	@$(SYS_PY) $(ROOT)/tools/make_compat_packages.py $(WS)/src

#    Built with the venv python, so the devel-space relays of scripts/*
#    (what rosrun / roslaunch start) run with rospy AND pybullet.
#    Up to date, catkin_make takes ~0.7 s; the stamp skips even that.
CATKIN_MAKE = cd $(WS) && catkin_make --source $(WS)/src --build $(WS)/build \
  -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=$(VENV_PY) \
  -DCATKIN_ENABLE_TESTING=ON -j2 > $(WS)/build.log 2>&1 \
  || { tail -n 60 $(WS)/build.log; echo "catkin_make failed (full log: .ws/build.log)" >&2; exit 1; }

$(STAMPS)/build: $(STAMPS)/venv $(BUILD_INPUTS) | link-package
	$(CATKIN_MAKE)
	@echo "build: ok (log in .ws/build.log)"
	@touch $@

build: $(STAMPS)/venv link-package
	$(CATKIN_MAKE)
	@echo "build: ok (log in .ws/build.log)"
	@touch $(STAMPS)/build

demo: setup
	$(WS_SHELL) python3 -m _arm1sim.session.demo

# Retake docs/images/web-view.png (session/web_picture.py): waits for the world at real time.
web-picture: setup
	$(WS_SHELL) python -m _arm1sim.session.web_picture

test: setup
	$(WS_SHELL) python test/run_all.py

# make test from a fresh clone of HEAD, STRESS_RUNS times in a row, while stress-ng keeps one
# core busy, then as many times with two busy (each number of STRESS_BUSY in turn): the check
# that no test judges in wall time what a busy machine stretches. stress-ng is needed by this
# target alone, so make setup does not install it.
STRESS_RUNS ?= 3
STRESS_BUSY ?= 1 2
STRESS_APT_PACKAGES := stress-ng
test-stress:
	@missing=""; \
	for p in $(STRESS_APT_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' "$$p" 2>/dev/null | grep -q 'ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "test-stress: apt-get install$$missing"; \
	  $(SUDO) env LC_ALL=C DEBIAN_FRONTEND=noninteractive apt-get update -q; \
	  $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=$(APT_LOCK_TIMEOUT) \
	    install -y -q --no-install-recommends $$missing; \
	fi
	@failed=""; \
	for busy in $(STRESS_BUSY); do \
	  BUSY=$$busy $(ROOT)/tools/test-stress $(STRESS_RUNS) || failed="$$failed $$busy"; \
	done; \
	if [ -n "$$failed" ]; then echo "test-stress: failed with busy cores:$$failed"; exit 1; fi

# ruff (lint, format check) and mypy, as make test runs them first.
lint: setup
	cd $(ROOT) && $(VENV_PY) -m ruff check . && $(VENV_PY) -m ruff format --check . && $(VENV_PY) -m mypy

bench: setup
	$(WS_SHELL) python -m _arm1sim.bench

# Not part of make test: robot_spawn.launch + simple_mover + a camera viewer for SOAK_MINUTES.
SOAK_MINUTES ?= 10
soak: setup
	$(WS_SHELL) python -m _arm1sim.bench.soak --minutes $(SOAK_MINUTES)

clean:
	rm -rf $(WS)
