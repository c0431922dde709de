# PythonModule.pip_install (python/CMakeLists.txt): `pip install --no-build-isolation .` of the
# source tree into WORK_DIR/site, with FOGLAB_CMAKE_BUILD_DIR=BUILD_DIR so that setup.py
# reuses the build's objects, then `import foglab` from WORK_DIR and one call checked, and a ROS
# bag (written by FOGLAB_CLI) read through the plugin the package carries beside its module.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(ENV{FOGLAB_CMAKE_BUILD_DIR} ${BUILD_DIR})
execute_process(
  COMMAND ${PYTHON} -m pip install --no-build-isolation --no-deps --no-input
          --disable-pip-version-check --target ${WORK_DIR}/site ${SOURCE_DIR}
  WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "pip install failed (${status}):\n${out}")
endif()
set(ENV{PYTHONPATH} ${WORK_DIR}/site)
execute_process(
  COMMAND ${FOGLAB_CLI} generate --imu --hours 0.001 --seed 3 --out ${WORK_DIR}/imu.bag
  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "foglab generate --imu (a bag to read) failed (${status}):\n${out}")
endif()
execute_process(
  COMMAND ${PYTHON} -c "import foglab, numpy as np
taus, devs, errors, ns = foglab.compat.oadev(np.arange(100.0) ** 2, data_type='phase', taus=[1, 2])
assert list(taus) == [1.0, 2.0] and list(ns) == [98, 96], (taus, ns)
assert abs(devs[0] - 2 ** 0.5) < 1e-12 and abs(devs[1] - 2 * 2 ** 0.5) < 1e-12, devs
record = foglab.read('${WORK_DIR}/imu.bag')
plugins = [line.split()[-1] for line in open('/proc/self/maps') if 'foglab_rosbag' in line]
assert plugins and all(p.startswith('${WORK_DIR}/site/foglab/') for p in plugins), plugins
print('installed foglab', foglab.__version__, 'from', foglab.__file__, 'read the bag with', plugins[0])"
  WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the installed package does not work (${status}):\n${out}")
endif()
if(NOT out MATCHES "from ${WORK_DIR}/site/foglab/__init__.py")
  message(FATAL_ERROR "foglab was imported from elsewhere, not the installed copy:\n${out}")
endif()
message(STATUS "${out}")
