%%%
  VERSION:1
  LANGUAGE:ENGLISH
%%%
MODULE Print_0001
  ! fibrecell test chunk: job 42, chunk 1/3, layer 0 (pla), generator 0.1.0
  ! Two tools, TCP at each nozzle tip, head tilted 30 degrees about y for each nozzle.
  PERS tooldata tPLA := [TRUE,[[0.000000,-72.500000,118.300000],[0.965926,0.000000,0.258819,0.000000]],[0.850000,[0.000000,-20.000000,60.000000],[1,0,0,0],0,0,0]];
  PERS tooldata tCCF := [TRUE,[[0.000000,72.500000,118.300000],[0.965926,0.000000,-0.258819,0.000000]],[0.850000,[0.000000,20.000000,60.000000],[1,0,0,0],0,0,0]];
  PERS wobjdata wBed := [FALSE,TRUE,"",[[400.000000,-150.000000,120.000000],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];
  VAR speeddata vPrint := [30,500,5000,1000];
  VAR speeddata vTravel := [150,500,5000,1000];
  VAR triggdata tgPathStart;
  VAR triggdata tgPathEnd;
  CONST robtarget pSafe := [[0.000000,0.000000,80.000000],[0.000000,0.000000,1.000000,0.000000],[0,0,-1,1],[9E9,9E9,9E9,9E9,9E9,9E9]];

  PROC Print_0001()
    ConfJ \On;
    ConfL \Off;
    ! event numbers on the group output: 17 = path start, 18 = path end
    TriggIO tgPathStart, 0 \Start \GOp:=goEvent, 17;
    TriggEquip tgPathEnd, 0, 0.05 \GOp:=goEvent, 18;
    MoveJ pSafe, vTravel, fine, tPLA \WObj:=wBed;
    MoveL [[10.000000,20.000000,0.800000],[0.000000,0.000000,1.000000,0.000000],[0,0,-1,1],[9E9,9E9,9E9,9E9,9E9,9E9]], vTravel, fine, tPLA \WObj:=wBed;
    WaitDI diExtruderReady, 1;
    TriggL [[30.000000,20.000000,0.800000],[0.000000,0.000000,1.000000,0.000000],[0,0,-1,1],[9E9,9E9,9E9,9E9,9E9,9E9]], vPrint, tgPathStart, z0, tPLA \WObj:=wBed;
    MoveL [[30.000000,40.000000,0.800000],[0.000000,0.000000,1.000000,0.000000],[0,0,-1,1],[9E9,9E9,9E9,9E9,9E9,9E9]], vPrint, z0, tPLA \WObj:=wBed;
    TriggL [[10.000000,40.000000,0.800000],[0.000000,0.000000,1.000000,0.000000],[0,0,-1,1],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]], vPrint, tgPathEnd, fine, tPLA,\WObj:=wBed;
    MoveL Offs(pSafe,0,0,20), v100, fine, tPLA \WObj:=wBed;
  ENDPROC
ENDMODULE
