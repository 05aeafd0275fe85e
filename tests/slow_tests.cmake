# Read by CTest after the discovered tests (TEST_INCLUDE_FILES, tests/CMakeLists.txt): the tests
# that take longest start first, so that the suite's wall time is set by the longest one and not
# by a long one that happened to start last. CTest orders by COST, highest first; after a run it
# orders by the times it measured (Testing/Temporary/CTestCostData.txt), but a fresh build
# directory has none. Seconds each, ASan build, idle 2-core machine (tools/build-times.sh prints
# them again); a test missing here only starts later.
set(fibrecell_slow_tests
    "ServiceTest.KilledMidPrintTheJobComesBackInterruptedAndResumesWithoutRepeats=22"
    "HeaterTest.TheHotendsGoOffWhenAPrintCompletesIsAbortedOrIsGivenUpAfterAFault=15"
    "ServiceTest.ABoardThatRestartsMidPrintIsConnectedAgainByTheResume=22"
    "MechanicsStage.OnTheLoopTheFieldBeatsContourZigzagAtTheSameFibre=19"
    "ServiceTest.SubmitStartWatchFollowsTheJobToItsOutcome=18"
    "AvrBoardPrint.AWatchdogHaltDuringHeatUpRefusesTheStartWithTheFirmwaresErrorAndTheJobStaysStartable=18"
    "ServiceTest.AStopDoesNotWaitForPlanningPastItsGraceAndTheJobPlansAtTheNextStart=11"
    "ExampleGuarantees.Loop=12"
    "ServiceTest.TheJobsSettingsReachTheBoardAndTheRobot=10"
    "ReferenceGuarantees.YogaNew=13"
    "ReferenceGuarantees.Bunnyhead=10"
    "ServiceTest.APlanForACellThatChangedIsRefusedUntilItIsReplanned=9"
    "ServiceTest.AJobIsPlannedAndPrintedWhileTwoClientsWatchIt=9"
    "ServiceTest.APrintThatFellShortOfItsPlanEndsCompletedWithWarnings=9"
    "ServiceTest.AJobThatCannotBePlannedFailsWhileAnotherPrints=9"
    "Gt2560Avr.AnInvertedDirectionBuildFeedsForwardOnlyWhenTheSimulatorIsToldSo=9"
    "Gt2560Avr.CountsStepPulsesIntoMillimetresAtTheFeedRate=8"
    "PrintCellTest.AFourCutJobRunsTheExactBoardLogAtTimeScale20=8"
    "FibreBudget.ABaselineBudgetTheLayerCannotHoldIsApproachedAndReported=7"
    "SyncFaultTest.ANewEngineResumesAnInterruptedFibreFeedWithNothingLostOrRepeated=7"
    "ServiceTest.APausedJobsHeatersGoOffAfterTheTimeOutAndResumeHeatsFirst=7")
# A name that is not a test here (one skipped at configure time) is passed over by CTest;
# `if(TEST ...)` cannot tell in this file: CTest's scripts do not know it, and it is always false.
foreach(entry IN LISTS fibrecell_slow_tests)
    string(REPLACE "=" ";" entry "${entry}")
    list(GET entry 0 name)
    list(GET entry 1 seconds)
    set_tests_properties("${name}" PROPERTIES COST ${seconds})
endforeach()
