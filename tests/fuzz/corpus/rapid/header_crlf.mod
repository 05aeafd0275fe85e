%%%
  VERSION:1
  LANGUAGE:ENGLISH
%%%
MODULE FcChunk0001
  VAR triggdata tgEv;
  PROC FcChunk0001()
    TriggIO tgEv, 0 \Start \GOp:=goFcEvent, 3;
    TriggL Offs(pZero, 1, 2, 0), v100, tgEv, z1, tool0;
    SetGO goFcEvent, 4;
  ENDPROC
  CONST robtarget pZero := [[0,0,1],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];
ENDMODULE
