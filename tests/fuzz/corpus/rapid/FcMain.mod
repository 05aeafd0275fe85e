MODULE FcMain
  ! fibrecell test resident main: waits for a job, then loads and runs its chunk modules one
  ! after another, loading the next chunk in the background while the current one prints.
  PERS num nChunks := 0;
  PERS string sJobDir := "HOME:/fibrecell/job";
  VAR num nChunk := 0;
  VAR string sModule := "";
  VAR loadsession lsNext;
  VAR intnum iAbort;
  CONST num EV_IDLE := 0;
  CONST num EV_JOB_START := 1;
  CONST num EV_JOB_END := 2;

  PROC main()
    ConfJ \On;
    SetGO goEvent, EV_IDLE;
    CONNECT iAbort WITH tAbort;
    ISignalDI diAbort, 1, iAbort;
    WHILE TRUE DO
      WaitDI diJobReady, 1;
      SetGO goEvent, EV_JOB_START;
      nChunk := 1;
      IF nChunks > 0 StartLoad \Dynamic, sJobDir \File:=ChunkName(1) + ".mod", lsNext;
      WHILE nChunk <= nChunks DO
        WaitLoad lsNext;
        sModule := ChunkName(nChunk);
        IF nChunk < nChunks THEN
          StartLoad \Dynamic, sJobDir \File:=ChunkName(nChunk + 1) + ".mod", lsNext;
        ELSEIF nChunk = nChunks THEN
          TPWrite "fibrecell: last chunk " + sModule;
        ELSE
          Stop;
        ENDIF
        %sModule + ":" + sModule%;
        UnLoad sJobDir \File:=sModule + ".mod";
        Incr nChunk;
      ENDWHILE
      TEST nChunks
      CASE 0:
        TPWrite "fibrecell: empty job";
      CASE 1, 2, 3:
        TPWrite "fibrecell: short job, chunks" \Num:=nChunks;
      DEFAULT:
        TPWrite "fibrecell: job done, chunks" \Num:=nChunks;
      ENDTEST
      %"FcMain:GoSafe"%;
      SetGO goEvent, EV_JOB_END;
      WaitDI diJobReady, 0;
    ENDWHILE
  ENDPROC

  PROC GoSafe()
    MoveJ Offs(CRobT(\Tool:=tool0 \WObj:=wobj0), 0, 0, 50), v200, fine, tool0;
  ENDPROC

  FUNC string ChunkName(num n)
    VAR string s;
    s := NumToStr(n, 0);
    WHILE StrLen(s) < 4 DO
      s := "0" + s;
    ENDWHILE
    RETURN "Print_" + s;
  ENDFUNC

  TRAP tAbort
    StopMove;
    SetGO goEvent, EV_IDLE;
    ExitCycle;
  ENDTRAP
ENDMODULE
