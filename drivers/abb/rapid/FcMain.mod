MODULE FcMain
  ! fibrecell resident main module for the IRC5 (RobotWare 6), task T_ROB1.
  ! Installed once on the controller (docs/irc5-setup.md); never generated per job.
  !
  ! Runs a print job made of chunk modules FcChunk0001.mod, FcChunk0002.mod, ... that the
  ! service (fibrecelld) uploads into a job folder. Each chunk holds one PROC named like its
  ! module; this module loads the chunks one after another with StartLoad \Dynamic, links the
  ! next one with WaitLoad, calls it by late binding and unloads it. The following chunk loads
  ! in the background while the current one runs. Chunks end at a travel move with fine.
  !
  ! Signals (I/O configuration, wired to the service's Modbus TCP coupler):
  !   diFcPause      in   pause request: StopMove while high, StartMove when it drops
  !   diFcAbort      in   abort request: stop, clear the path, unload chunks, back to idle
  !   diFcHeartbeat  in   toggled by the service about every 100 ms
  !   giFcRelease    in   16 bit: barrier release, the number of the barrier to release
  !   doFcRunning    out  high while a run is in progress (low when held on heartbeat loss)
  !   doFcHeartbeat  out  toggled by this module every 100 ms
  !   goFcEvent      out  16 bit: last event number (chunk triggers and barriers)
  !   goFcBarrier    out  16 bit: number of the barrier waited for last
  !
  ! None of this is a safety function: emergency stops, guards and enabling devices are
  ! wired to the controller's safety circuits, independent of this module and the service.

  ! ---- Job parameters: written by the service over RWS before it sets bFcRun ----
  ! Job folder on the controller, no trailing "/", at most 60 characters.
  PERS string sFcJobDir := "HOME:/fibrecell/job";
  ! Number of chunk modules in the job, 1..9999.
  PERS num nFcChunkCount := 0;
  ! First chunk to run: 1 for a new job, k to resume a job at FcChunk<k>.
  PERS num nFcFirstChunk := 1;
  ! Heartbeat timeout in seconds (0.3..10); read when a run request is taken.
  PERS num nFcHbTimeout := 1;
  ! Run request: set TRUE by the service; cleared by this module when it takes the request.
  PERS bool bFcRun := FALSE;

  ! ---- Status: written by this module, read by the service over RWS ----
  ! 0 idle, 1 running, 2 paused, 3 held (heartbeat lost), 4 completed, 5 aborted, 6 rejected.
  PERS num nFcState := 0;
  ! Chunk being executed (after an abort: the chunk it stopped in; 0 after a completed run)
  ! and the last chunk completed in the current or last run (resume at nFcChunkDone + 1).
  PERS num nFcChunkNow := 0;
  PERS num nFcChunkDone := 0;
  ! Number of the barrier waited for last.
  PERS num nFcBarrier := 0;
  ! Why the last run was rejected or stopped ("" when it completed).
  PERS string sFcMessage := "";

  CONST num FC_IDLE := 0;
  CONST num FC_RUNNING := 1;
  CONST num FC_PAUSED := 2;
  CONST num FC_HELD := 3;
  CONST num FC_DONE := 4;
  CONST num FC_ABORTED := 5;
  CONST num FC_REJECTED := 6;
  ! Heartbeat timer period in seconds (the shortest cyclic ITimer period).
  CONST num FC_TICK := 0.1;
  ! Event and barrier numbers travel on 16-bit groups.
  CONST num FC_SEQ_MOD := 65536;
  ! Seconds a run request may wait for heartbeat, pause, abort and release preconditions.
  CONST num FC_START_WAIT := 2;

  LOCAL VAR intnum iFcAbort;
  LOCAL VAR intnum iFcPauseOn;
  LOCAL VAR intnum iFcPauseOff;
  LOCAL VAR intnum iFcHbRise;
  LOCAL VAR intnum iFcHbFall;
  LOCAL VAR intnum iFcTick;
  LOCAL VAR loadsession lsFcChunk;
  ! File of the chunk being loaded in the background (StartLoad done, WaitLoad not yet).
  LOCAL VAR string sFcNextPath := "";
  ! File and routine of the linked chunk (WaitLoad done, UnLoad not yet).
  LOCAL VAR string sFcCurPath := "";
  LOCAL VAR string sFcCurName := "";
  ! FALSE after a program reset (PP to main); kept TRUE across ExitCycle.
  LOCAL VAR bool bFcStarted := FALSE;
  ! A run is in progress.
  LOCAL VAR bool bFcJob := FALSE;
  ! The pause request is active.
  LOCAL VAR bool bFcPause := FALSE;
  ! Stopped on heartbeat loss; waits for a resume (pause request 1 then 0) or an abort.
  LOCAL VAR bool bFcHeld := FALSE;
  ! While held: the pause request rose with the heartbeat back, so its drop is a resume.
  LOCAL VAR bool bFcResumeArmed := FALSE;
  ! A heartbeat edge was seen within the timeout.
  LOCAL VAR bool bFcHbOk := FALSE;
  ! StopMove issued by this module and not yet undone by StartMove.
  LOCAL VAR bool bFcStopped := FALSE;
  ! Timer ticks since the last heartbeat edge, and the ticks that make the timeout.
  LOCAL VAR num nFcHbAge := 0;
  LOCAL VAR num nFcHbLimit := 10;
  LOCAL VAR num nFcHbOut := 0;

  PROC main()
    FcInit;
    WHILE TRUE DO
      FcWaitRun;
      IF bFcJob FcRunJob;
    ENDWHILE
  ENDPROC

  ! Barrier, called by a chunk after a fine point: publish the barrier number and wait until
  ! the service releases it (giFcRelease = number). Abort (TRAP, ExitCycle) and heartbeat
  ! loss (held: no release is taken until the run is resumed) are honoured while waiting.
  PROC FcBarrier(num nSeq)
    VAR num nCode;
    nCode := nSeq MOD FC_SEQ_MOD;
    nFcBarrier := nCode;
    SetGO goFcBarrier, nCode;
    SetGO goFcEvent, nCode;
    WaitUntil \InPos, GInput(giFcRelease) = nCode AND NOT bFcHeld \PollRate:=0.04;
  ENDPROC

  ! Start of a cycle: after a program reset, or after an abort (ExitCycle keeps VAR values,
  ! interrupts and loaded modules, so clean up what the interrupted run left behind).
  LOCAL PROC FcInit()
    bFcJob := FALSE;
    bFcHeld := FALSE;
    SetDO doFcRunning, 0;
    IF NOT bFcStarted THEN
      ! A run request left over from before the reset must not start motion.
      bFcRun := FALSE;
      IF nFcState = FC_RUNNING OR nFcState = FC_PAUSED OR nFcState = FC_HELD THEN
        nFcState := FC_IDLE;
        sFcMessage := "run interrupted by a program reset";
      ENDIF
      bFcStarted := TRUE;
    ENDIF
    FcUnloadAll;
    nFcHbLimit := FcHbTicks();
    nFcHbAge := nFcHbLimit;
    bFcHbOk := FALSE;
    IDelete iFcAbort;
    CONNECT iFcAbort WITH FcOnAbort;
    ISignalDI diFcAbort, 1, iFcAbort;
    IDelete iFcPauseOn;
    CONNECT iFcPauseOn WITH FcOnPause;
    ISignalDI diFcPause, 1, iFcPauseOn;
    IDelete iFcPauseOff;
    CONNECT iFcPauseOff WITH FcOnResume;
    ISignalDI diFcPause, 0, iFcPauseOff;
    IDelete iFcHbRise;
    CONNECT iFcHbRise WITH FcOnHbEdge;
    ISignalDI diFcHeartbeat, 1, iFcHbRise;
    IDelete iFcHbFall;
    CONNECT iFcHbFall WITH FcOnHbEdge;
    ISignalDI diFcHeartbeat, 0, iFcHbFall;
    IDelete iFcTick;
    CONNECT iFcTick WITH FcOnTick;
    ITimer FC_TICK, iFcTick;
    bFcPause := DInput(diFcPause) = 1;
    FcApplyHold;
  ENDPROC

  ! Wait for a run request and check it; sets bFcJob when the run may start.
  LOCAL PROC FcWaitRun()
    VAR bool bLate := FALSE;
    VAR string sWhy := "";
    WaitUntil bFcRun \PollRate:=0.1;
    nFcHbLimit := FcHbTicks();
    WaitUntil bFcHbOk AND NOT bFcPause AND DInput(diFcAbort) = 0 AND GInput(giFcRelease) = 0
      \MaxTime:=FC_START_WAIT \TimeFlag:=bLate;
    IF bLate THEN
      sWhy := FcStartProblem();
    ELSE
      sWhy := FcJobProblem();
    ENDIF
    ! bFcRun drops only once the answer (nFcState) is published.
    IF sWhy <> "" THEN
      sFcMessage := sWhy;
      nFcState := FC_REJECTED;
      bFcRun := FALSE;
      TPWrite "FcMain: run rejected: " + sWhy;
    ELSE
      FcStartRun;
    ENDIF
  ENDPROC

  ! Publish the start of a run: event and barrier groups to 0, system default motion
  ! settings, doFcRunning high, state running; then take the request.
  LOCAL PROC FcStartRun()
    sFcMessage := "";
    nFcChunkNow := 0;
    nFcChunkDone := nFcFirstChunk - 1;
    nFcBarrier := 0;
    SetGO goFcBarrier, 0;
    SetGO goFcEvent, 0;
    AccSet 100, 100;
    VelSet 100, 5000;
    ConfJ \On;
    ConfL \On;
    SingArea \Off;
    bFcHeld := FALSE;
    SetDO doFcRunning, 1;
    nFcState := FC_RUNNING;
    bFcRun := FALSE;
    bFcJob := TRUE;
    FcShowState;
  ENDPROC

  ! One run: chunks nFcFirstChunk..nFcChunkCount. The abort interrupt sleeps while a load,
  ! link or unload and its bookkeeping run, so that an abort never splits them; the abort
  ! input is checked right after (the service holds it high until it sees the run stop).
  LOCAL PROC FcRunJob()
    VAR num nNow := 0;
    VAR string sPath := "";
    nNow := nFcFirstChunk;
    sPath := FcChunkPath(nNow);
    ISleep iFcAbort;
    StartLoad \Dynamic, sPath, lsFcChunk;
    sFcNextPath := sPath;
    IWatch iFcAbort;
    FcCheckAbort;
    WHILE nNow <= nFcChunkCount DO
      ISleep iFcAbort;
      WaitLoad lsFcChunk;
      sFcCurPath := sFcNextPath;
      sFcCurName := FcChunkName(nNow);
      sFcNextPath := "";
      IF nNow < nFcChunkCount THEN
        sPath := FcChunkPath(nNow + 1);
        StartLoad \Dynamic, sPath, lsFcChunk;
        sFcNextPath := sPath;
      ENDIF
      IWatch iFcAbort;
      FcCheckAbort;
      nFcChunkNow := nNow;
      %sFcCurName%;
      ISleep iFcAbort;
      UnLoad sFcCurPath;
      sFcCurPath := "";
      sFcCurName := "";
      nFcChunkDone := nNow;
      IWatch iFcAbort;
      FcCheckAbort;
      nNow := nNow + 1;
    ENDWHILE
    bFcJob := FALSE;
    bFcHeld := FALSE;
    SetDO doFcRunning, 0;
    nFcChunkNow := 0;
    nFcState := FC_DONE;
    FcApplyHold;
  ENDPROC

  ! Unload whatever an interrupted run left: a chunk loading in the background, a linked one.
  LOCAL PROC FcUnloadAll()
    IF sFcNextPath <> "" THEN
      WaitLoad lsFcChunk;
      UnLoad sFcNextPath;
      sFcNextPath := "";
    ENDIF
    IF sFcCurPath <> "" THEN
      UnLoad sFcCurPath;
      sFcCurPath := "";
      sFcCurName := "";
    ENDIF
  ENDPROC

  LOCAL PROC FcCheckAbort()
    IF DInput(diFcAbort) = 1 FcAbort;
  ENDPROC

  ! Stop the motion, drop the rest of the path and restart the cycle (FcInit unloads the
  ! chunks). The robot stays where it stopped. Does nothing when no run is in progress.
  LOCAL PROC FcAbort()
    IF bFcJob THEN
      StopMove;
      ClearPath;
      StartMove;
      bFcStopped := FALSE;
      bFcJob := FALSE;
      bFcHeld := FALSE;
      bFcRun := FALSE;
      SetDO doFcRunning, 0;
      nFcState := FC_ABORTED;
      sFcMessage := "aborted by the service";
      ExitCycle;
    ENDIF
  ENDPROC

  ! StopMove while paused or held, StartMove when neither; issued once per change.
  LOCAL PROC FcApplyHold()
    IF (bFcPause OR bFcHeld) AND NOT bFcStopped THEN
      StopMove;
      bFcStopped := TRUE;
    ELSEIF NOT (bFcPause OR bFcHeld) AND bFcStopped THEN
      StartMove;
      bFcStopped := FALSE;
    ENDIF
  ENDPROC

  LOCAL PROC FcShowState()
    IF bFcJob THEN
      IF bFcHeld THEN
        nFcState := FC_HELD;
      ELSEIF bFcPause THEN
        nFcState := FC_PAUSED;
      ELSE
        nFcState := FC_RUNNING;
      ENDIF
    ENDIF
  ENDPROC

  ! "FcChunk0007" for 7: module name, file stem and routine name of a chunk.
  LOCAL FUNC string FcChunkName(num nIndex)
    VAR string sDigits := "";
    sDigits := NumToStr(nIndex, 0);
    WHILE StrLen(sDigits) < 4 DO
      sDigits := "0" + sDigits;
    ENDWHILE
    RETURN "FcChunk" + sDigits;
  ENDFUNC

  ! The chunk's file in the job folder, e.g. "HOME:/fibrecell/job-12/FcChunk0007.mod".
  LOCAL FUNC string FcChunkPath(num nIndex)
    VAR string sLast := "";
    sLast := StrPart(sFcJobDir, StrLen(sFcJobDir), 1);
    IF sLast = "/" OR sLast = ":" THEN
      RETURN sFcJobDir + FcChunkName(nIndex) + ".mod";
    ENDIF
    RETURN sFcJobDir + "/" + FcChunkName(nIndex) + ".mod";
  ENDFUNC

  ! The heartbeat timeout in timer ticks, kept within 3..100 (0.3 s..10 s).
  LOCAL FUNC num FcHbTicks()
    VAR num nTicks := 10;
    nTicks := Round(nFcHbTimeout / FC_TICK);
    IF nTicks < 3 THEN
      nTicks := 3;
    ELSEIF nTicks > 100 THEN
      nTicks := 100;
    ENDIF
    RETURN nTicks;
  ENDFUNC

  ! Why the run preconditions did not hold within FC_START_WAIT.
  LOCAL FUNC string FcStartProblem()
    IF NOT bFcHbOk THEN
      RETURN "no heartbeat from the service";
    ELSEIF bFcPause THEN
      RETURN "pause request is active";
    ELSEIF DInput(diFcAbort) = 1 THEN
      RETURN "abort request is active";
    ENDIF
    RETURN "barrier release is not 0";
  ENDFUNC

  ! Why the job parameters cannot run ("" when they can).
  LOCAL FUNC string FcJobProblem()
    IF nFcChunkCount < 1 OR nFcChunkCount > 9999 OR nFcChunkCount <> Trunc(nFcChunkCount) THEN
      RETURN "chunk count must be a whole number 1..9999";
    ENDIF
    IF nFcFirstChunk < 1 OR nFcFirstChunk > nFcChunkCount
      OR nFcFirstChunk <> Trunc(nFcFirstChunk) THEN
      RETURN "first chunk must be a whole number 1..chunk count";
    ENDIF
    IF StrLen(sFcJobDir) < 1 OR StrLen(sFcJobDir) > 60 THEN
      RETURN "job folder must have 1..60 characters";
    ENDIF
    FOR i FROM nFcFirstChunk TO nFcChunkCount DO
      IF NOT IsFile(FcChunkPath(i)) THEN
        RETURN "missing " + FcChunkName(i) + ".mod in the job folder";
      ENDIF
    ENDFOR
    RETURN "";
  ENDFUNC

  LOCAL TRAP FcOnAbort
    FcAbort;
  ENDTRAP

  LOCAL TRAP FcOnPause
    bFcPause := TRUE;
    IF bFcHeld AND bFcHbOk THEN
      bFcResumeArmed := TRUE;
    ENDIF
    FcApplyHold;
    FcShowState;
  ENDTRAP

  ! The pause request dropped: resume. After a heartbeat loss the resume is taken only when
  ! the request rose and dropped again while the heartbeat was back.
  LOCAL TRAP FcOnResume
    bFcPause := FALSE;
    IF bFcHeld AND bFcHbOk AND bFcResumeArmed THEN
      bFcHeld := FALSE;
      bFcResumeArmed := FALSE;
      IF bFcJob SetDO doFcRunning, 1;
      sFcMessage := "";
    ENDIF
    FcApplyHold;
    FcShowState;
  ENDTRAP

  LOCAL TRAP FcOnHbEdge
    nFcHbAge := 0;
    bFcHbOk := TRUE;
  ENDTRAP

  ! Every FC_TICK: toggle the robot heartbeat and age the service's one; on a timeout during a
  ! run, stop the motion and hold until a resume or an abort.
  LOCAL TRAP FcOnTick
    nFcHbOut := 1 - nFcHbOut;
    SetDO doFcHeartbeat, nFcHbOut;
    IF nFcHbAge < nFcHbLimit Incr nFcHbAge;
    IF nFcHbAge >= nFcHbLimit THEN
      bFcHbOk := FALSE;
    ENDIF
    IF bFcJob AND NOT bFcHbOk AND NOT bFcHeld THEN
      bFcHeld := TRUE;
      bFcResumeArmed := FALSE;
      SetDO doFcRunning, 0;
      sFcMessage := "heartbeat lost: held, waiting for resume or abort";
      FcApplyHold;
      FcShowState;
      TPWrite "FcMain: service heartbeat lost, motion stopped";
    ENDIF
  ENDTRAP
ENDMODULE
