# Read by CTest after the discovered tests (TEST_INCLUDE_FILES, tests/CMakeLists.txt): the tests
# that take longest start first, so that the suite's wall time is set by the longest one and not
# by a long one that happened to start last. CTest orders by COST, highest first; after a run it
# orders by the times it measured (Testing/Temporary/CTestCostData.txt), but a fresh build
# directory has none. Seconds each, ASan build, idle 2-core machine (tools/build-times.sh prints
# them again; last measured 2026-12-07); a test missing here only starts later. The timing
# test (PrintPositionTest) runs alone anyway.
set(fibrecell_slow_tests
    "FibreBudget.EveryStrategyLaysTheMetresPerLayerAskedWithinFivePercent=31"
    "ServiceTest.TheHistoryRecordsWhatTheBoardFedForACompletedAnAbortedAndAnInterruptedPrint=23"
    "ReferenceGuarantees.YogaNew=22"
    "ServiceTest.QueuedJobsPrintInOrderOnePerClearAndTheQueueSurvivesAKill=22"
    "MechanicsStage.OnTheLoopTheFieldBeatsContourZigzagAtTheSameFibre=20"
    "AvrBoardPrint.AWatchdogHaltDuringHeatUpRefusesTheStartWithTheFirmwaresErrorAndTheJobStaysStartable=17"
    "ExampleGuarantees.Loop=16"
    "ReferenceGuarantees.Bunnyhead=15"
    "ServiceTest.KilledMidPrintTheJobComesBackInterruptedAndResumesWithoutRepeats=15"
    "ReferenceGuarantees.BunnyheadFieldDense=13"
    "ExampleGuarantees.LoopFieldDense=12"
    "HeaterTest.TheHotendsGoOffWhenAPrintCompletesIsAbortedOrIsGivenUpAfterAFault=12"
    "ServiceTest.AByHandQueueRefusesBadCallsAndPausesAfterAnAbortedPrint=12"
    "ServiceTest.SubmitStartWatchFollowsTheJobToItsOutcome=12"
    "FibreBudget.BothStrategiesLayTheMetresPerLayerAskedWithinFivePercent=9"
    "Gt2560Avr.AnInvertedDirectionBuildFeedsForwardOnlyWhenTheSimulatorIsToldSo=9"
    "FibreBudget.ABaselineBudgetTheLayerCannotHoldIsApproachedAndReported=8"
    "FibreBudget.MoreThanTheJobLaysIsMetByLoweringTheContrastFirst=8"
    "Gt2560Avr.CountsStepPulsesIntoMillimetresAtTheFeedRate=8"
    "PrintCellTest.AFourCutJobRunsTheExactBoardLogAtTimeScale20=8"
    "ServiceTest.ASpoolTooShortRefusesTheJobAndAPrintTakesOffWhatTheBoardFed=8"
    "layering=8"
    "HeaterTest.AHoldKeepsThemHotForTheNextPrintThenTheyGoOff=7"
    "HeaterTest.AnIdleCellTurnsThemOffAndSoDoesAServiceThatStops=7"
    "ServiceTest.AFullDiskMidPrintHoldsTheCellAndKeepsTheServiceAnswering=7"
    "ServiceTest.APrintThatFellShortOfItsPlanEndsCompletedWithWarnings=7"
    "ServiceTest.KilledMidPrintTheSpoolsLoseAtMostALayerAndTheNextStartSaysWhatItCharged=7"
    "ServiceTest.KilledWhileWritingAPlanNeverLeavesAPlannedJobWithABadFile=7"
    "ServiceTest.TheJobsSettingsReachTheBoardAndTheRobot=7"
    "SyncFaultTest.ANewEngineResumesAnInterruptedFibreFeedWithNothingLostOrRepeated=7"
    "Gt2560Avr.TheHeatingWatchdogHaltsAHotendThatDoesNotHeatUntilAReset=6"
    "ServiceTest.ABoardThatRestartsMidPrintIsConnectedAgainByTheResume=6"
    "ServiceTest.AJobIsPlannedAndPrintedWhileTwoClientsWatchIt=6"
    "ServiceTest.AJobThatCannotBePlannedFailsWhileAnotherPrints=6"
    "ServiceTest.APausedJobsHeatersGoOffAfterTheTimeOutAndResumeHeatsFirst=6"
    "ServiceTest.APlanForACellThatChangedIsRefusedUntilItIsReplanned=6")
# A name that is not a test here (one skipped at configure time) is passed over by CTest;
# `if(TEST ...)` cannot tell in this file: CTest's scripts do not know it, and it is always false.
foreach(entry IN LISTS fibrecell_slow_tests)
    string(REPLACE "=" ";" entry "${entry}")
    list(GET entry 0 name)
    list(GET entry 1 seconds)
    set_tests_properties("${name}" PROPERTIES COST ${seconds})
endforeach()
