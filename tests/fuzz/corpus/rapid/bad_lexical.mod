MODULE Bad
  VAR num aVeryLongIdentifierThatIsOver32Chars := 1;
  CONST string s := "unterminated;
  VAR num x{0};
  VAR num y{100001};
ENDMODULE
MODULE Two
ENDMODULE
