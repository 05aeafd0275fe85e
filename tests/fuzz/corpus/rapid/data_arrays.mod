MODULE FcData(SYSMODULE, NOSTEPIN)
  ! Module data the loader instantiates: arrays, records, constants built from earlier ones.
  CONST num nRows := 3;
  CONST num nTable{nRows, 2} := [[1, 2], [3, 4], [5, 6]];
  VAR pos pOffsets{2} := [[0, 0, 5], [1.5, -2, .5]];
  PERS dnum dCount := 0x1F;
  VAR bool bFlags{4};
  CONST string sName := "FcChunk" + NumToStr(1, 0) + "\41";
  CONST orient oTilt := OrientZYX(0, 30, 0);
  VAR robjoint jHome := [0, 0, 0, 0, 90, 0];
  CONST jointtarget jtHome := [[0, 0, 0, 0, 90, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]];
  CONST zonedata zTight := [FALSE, 0.3, 0.5, 0.5, 0.05, 0.5, 0.05];
  VAR num nSum := Abs(-2) * Pow(2, 3) DIV 3 MOD 5 + Round(1.2345 \Dec:=2);

  LOCAL FUNC num Sum(num a{*}, \switch Twice)
    VAR num s := 0;
    FOR i FROM 1 TO Dim(a, 1) STEP 1 DO
      s := s + a{i};
    ENDFOR
    IF Present(Twice) s := 2 * s;
    RETURN s;
  ENDFUNC

  PROC main()
    VAR num n;
    n := nTable{2, 1} + pOffsets{1}.z;
    bFlags{1} := n > 7 AND NOT bFlags{2} XOR TRUE;
    MoveAbsJ jtHome, v100, fine, tool0;
    MoveJ [[10,0,80],oTilt,[0,0,-1,1],[9E9,9E9,9E9,9E9,9E9,9E9]], v200, zTight, tool0;
    WaitTime 0.5;
    TPWrite sName \Num:=n;
  ENDPROC
ENDMODULE
