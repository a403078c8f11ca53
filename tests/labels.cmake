# Labels every test of tessera_tests with its tier (tests/README.md, "Tiers"): exactly one
# of unit, statistical, cli, bench; and gives the tests that start Xvfb one resource lock,
# and those that run mpirun another. Included by CTest after gtest_discover_tests' list
# (tests/CMakeLists.txt), where tessera_tests_TESTS holds every discovered test name, e.g.
# `Methods/Contact.CornerWhereTheLightMeetsTheWallsStaysBounded/pt_Embree`.
# A test no pattern matches is unit: a new test that renders many samples belongs in
# the statistical pattern, or `ctest -L unit` stops being fast.

# Run the tessera executable.
set(tessera_cli_tests "^([A-Za-z]+/)?[A-Za-z]+Cli\\.")
# Run the bench/ scripts.
set(tessera_bench_tests "^(AccuracyReport|AccuracySweep|AisBound|Flicker|BoxDownsample)\\.")
# Render many samples and compare statistics: hard cases, analytic and furnace tests,
# chi-square and moment tests of the sampling routines, backend agreement, error orders.
set(tessera_statistical_tests
    "^Methods/"
    "^Backends/(PtFurnace|PtMedium|PlaneUnderLight|InstantCacheOn|IcPassesOn)\\."
    "^(BackendAgreement|PtAgreement|Traversal|IgiAgreement|IgiConvergence|IgiMedia|Ais|LightSelection|PassConvergence)\\."
    "^G/HenyeyGreenstein\\.SamplesMatchThePhaseFunction/"
    "^Sampling\\.(CosineHemisphereMatchesItsPdf|UniformHemisphereMatchesItsPdf|TriangleBarycentricsAreUniformInArea|LightSelectionFollowsPower)$"
    "^SphericalTriangle\\.(SamplesAreUniformInSolidAngle|RelabelledTrianglesAreUniformInSolidAngle|SliversSeenEdgeOnAreUniformInSolidAngle)$"
    "^LightSampleFrom\\.(NearALightMatchesLambertAndEachSampleIsBounded|SliversSeenEdgeOnMatchLambert)$"
    "^Medium\\.(FreeFlightDistancesAreExponential|RgbWeightsAreUnbiased|EquiangularDistancesFollowTheirPdf)$"
    "^EdgeSamples\\.EachSampleIsUniformOverThePixel$")
list(JOIN tessera_statistical_tests "|" tessera_statistical_tests)
# Start an X server (tests/support/with-xvfb, which says why the viewer tests once failed
# with "Failed to open display"). They also hold one lock, so CTest never starts two X
# servers at once: a server trying a display number removes that display's socket file
# before it binds its own (xtrans), which could take the file from a server starting
# beside it.
set(tessera_xvfb_tests "^([A-Za-z]+/)?ViewWindowCli\\.")
# Run mpirun: one lock too. Two Open MPI launches at once race on their shared session
# directory (/tmp/ompi.<host>.<uid>): one removes it as it ends while the other is making
# its own below it, and the second fails with "A call to mkdir was unable to create the
# desired directory ... File exists" (seen once in a ctest -j2 run).
set(tessera_mpi_tests "^DistributedCli\\.")

foreach(test IN LISTS tessera_tests_TESTS)
  if(test MATCHES "${tessera_cli_tests}")
    set(label cli)
  elseif(test MATCHES "${tessera_bench_tests}")
    set(label bench)
  elseif(test MATCHES "${tessera_statistical_tests}")
    set(label statistical)
  else()
    set(label unit)
  endif()
  set_tests_properties("${test}" PROPERTIES LABELS ${label})
  if(test MATCHES "${tessera_xvfb_tests}")
    set_tests_properties("${test}" PROPERTIES RESOURCE_LOCK xvfb)
  endif()
  if(test MATCHES "${tessera_mpi_tests}")
    set_tests_properties("${test}" PROPERTIES RESOURCE_LOCK mpirun)
  endif()
endforeach()
