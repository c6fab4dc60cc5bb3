# The Debian package: `cpack -G DEB` in the build directory after building writes
# vb_<version>_<arch>.deb with everything cmake/vb_install.cmake installs, under /usr.
# Depends are computed by dpkg-shlibdeps from the tools' shared libraries (on Debian 12:
# libbullet3.24, libyaml-cpp0.7, libassimp5, libopencv-core406 / -imgproc406, libpng16-16,
# libhdf5-103-1 (vb_collect), libstdc++6, libc6, libgcc-s1; the test DebPackageTest checks them).
# scripts/check_deb_clean_chroot.sh
# installs the package with apt into a fresh Debian 12 chroot and runs the README's example.
set(CPACK_PACKAGE_NAME vb)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_VENDOR "vb developers")
set(CPACK_PACKAGE_CONTACT "vb developers <vb@example.org>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "native C++ off-road mobility benchmark for vertically challenging terrain")
set(CPACK_PACKAGE_DESCRIPTION
    "vb runs navigation trials of ground vehicles over rocky, vertically challenging worlds and \
reports success, roll-overs and traversal times. Tools: vb_run, vb_batch, vb_report, vb_gen, \
vb_import, vb_view, vb_gym, vb_collect; the 100 benchmark tasks are in /usr/share/vb/tasks.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://example.org/vb")
# Only the project's own install rules (no test frameworks or third-party components).
set(CPACK_SOURCE_IGNORE_FILES "/build/;/\\\\.git/;/\\\\.venv/")
include(CPack)
