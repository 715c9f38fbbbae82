# Installs tests/host/view's npm packages into DST (the build directory) with `npm ci`, exactly the versions of
# package-lock.json, without install scripts (puppeteer-core downloads nothing; the tests use Debian's chromium).
# Skipped when DST already holds the install of this very lock file.
file(COPY ${SRC}/package.json ${SRC}/package-lock.json DESTINATION ${DST})
file(SHA256 ${SRC}/package-lock.json lock)
set(stamp ${DST}/node_modules/.voxcd-lock-sha256)
if(EXISTS ${stamp})
  file(READ ${stamp} have)
  if(have STREQUAL lock)
    message(STATUS "puppeteer-core is installed in ${DST}/node_modules")
    return()
  endif()
endif()
execute_process(COMMAND ${NPM} ci --ignore-scripts --no-audit --no-fund WORKING_DIRECTORY ${DST} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "npm ci in ${DST} failed (${rc}): the npm registry must be reachable once to install puppeteer-core")
endif()
file(WRITE ${stamp} "${lock}")
