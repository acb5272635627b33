//! §12.4 statements: assignment, IF, FOR, REPEAT, WHILE, EXIT.
use linc_conformance::{invalid, valid};

valid!(s12_4_1_constant_to_real, "§12.4.1", Action, "PIC_004.PV:=35.5;\n");
valid!(s12_4_1_calculation_to_real, "§12.4.1", Action, "ANOP_3.PV:=Const.A6 + (Block_5.PV+3.5) / Const.A7;\n");
valid!(s12_4_1_constant_to_digital, "§12.4.1", Action, "Dig_B.Out.Bit0:=1;\n");
valid!(s12_4_1_calculation_to_digital, "§12.4.1", Action, "SEQ4.Hold:=(PIC_005.PV > 30) AND Dig_B.Out.Bit5;\n");
valid!(s12_4_1_string_to_mode, "§12.4.1", Action, "PIC_004.Mode:=\"CASCADE\";\n");
valid!(s12_4_1_integer_to_bitfield, "§12.4.1", Action, "Dig_A.Out:=96;\n");
valid!(s12_4_1_bitwise_to_bitfield, "§12.4.1", Action, "Dig_A.Out:=Dig_B.Out XOR 96;\n");
invalid!(s12_4_statement_needs_semicolon, "§12.4", Action, "TIC_100.PV := 1\nTIC_100.SL := 2;\n", ["E0010"]);
invalid!(
    s12_4_last_statement_without_semicolon_warns,
    "§12.4",
    Action,
    "TIC_100.PV := 1;\nTIC_100.SL := 2\n",
    ["W0001"]
);
valid!(
    s12_4_2_if_else,
    "§12.4.2",
    Action,
    "IF PIC_004.PV < 10 THEN\nDig_B.Out.Bit0 := 1;\nRECORD.A4 := ANIN_004.HR;\nELSE\nDig_B.Out.Bit1 := 1;\nEND_IF;\n"
);
valid!(s12_4_2_elsif_chain_and_nesting, "§12.4.2", Action, "IF PIC_004.PV < 10 THEN\n  Dig_B.Out.Bit0 := 1;\nELSIF PIC_004.PV < 20 THEN\n  IF Dig_A.Out.Bit3 THEN Dig_B.Out.Bit1 := 1; END_IF;\nELSIF PIC_004.PV < 30 THEN\n  Dig_B.Out.Bit2 := 1;\nEND_IF;\n");
invalid!(s12_4_2_if_must_be_closed, "§12.4.2", Action, "IF PIC_004.PV < 10 THEN\nDig_B.Out.Bit0 := 1;\n", ["E0011"]);
invalid!(
    s12_4_2_condition_must_be_truth_value,
    "§12.4.2",
    Action,
    "IF PIC_004.PV THEN Dig_B.Out.Bit0 := 1; END_IF;\n",
    ["E0119"]
);
valid!(s12_4_2_integer_condition, "§12.4.2", Action, "IF Dig_A.Out AND 64 THEN Dig_B.Out.Bit0 := 1; END_IF;\n");
valid!(s12_4_3_for_average_example, "§12.4.3", Action, "avg:=0;\nFOR PIC_004.PV := 0 TO 10 BY 2 DO\navg := avg+f[PIC_004.PV]; (* offset value *)\nEND_FOR;\navg:=avg/5; (* Sum divided to calculate the average *)\n");
valid!(
    s12_4_3_for_negative_step,
    "§12.4.3",
    Action,
    "FOR Counters.N0 := 7 TO 0 BY -1 DO\n  Block_5.Val1{Counters.N0} := 0;\nEND_FOR;\n"
);
invalid!(
    s12_4_3_for_step_must_be_literal,
    "§12.4.3",
    Action,
    "FOR Counters.N0 := 0 TO 10 BY Counters.N1 DO\n  Counters.N2 := 1;\nEND_FOR;\n",
    ["E0106"]
);
invalid!(
    s12_4_3_for_must_be_closed,
    "§12.4.3",
    Action,
    "FOR Counters.N0 := 0 TO 10 DO\n  Counters.N2 := 1;\nEND_WHILE;\n",
    ["E0010", "E0011"]
);
invalid!(
    s12_4_3_for_index_must_be_numeric,
    "§12.4.3",
    Action,
    "FOR PIC_004.Mode := 0 TO 10 DO\n  Counters.N2 := 1;\nEND_FOR;\n",
    ["E0114"]
);
valid!(s12_4_4_repeat_example, "§12.4.4", Action, "REPEAT\nPIC_004.PV:= PIC_004.PV+1; (*array value *)\nUNTIL PIC_004.PV >= 10; (* repeat until variable reaches 10 or more\n*)\nEND_REPEAT;\n");
valid!(
    s12_4_4_repeat_without_semicolon_after_until,
    "§12.4.4",
    Action,
    "REPEAT PIC_004.PV := PIC_004.PV + 1; UNTIL PIC_004.PV >= 10 END_REPEAT;\n"
);
valid!(s12_4_5_while_example, "§12.4.5", Action, "avg:=0;\nPIC_004.PV := 0;\nWHILE PIC_004.PV<5 DO\navg := avg+f[PIC_004.PV]; (* array/offset value *)\nPIC_004.PV := PIC_004.PV+1;\nEND_WHILE;\navg:=avg/5; (* Sum divided to calculate the average *)\n");
valid!(s12_4_6_exit_in_while, "§12.4.6", Action, "WHILE PIC_004.PV < 100 DO\n   PIC_004.PV := PIC_004.PV + 1;\n   IF Dig_A.Out.Bit0 THEN\n      EXIT;\n   END_IF;\nEND_WHILE;\n");
valid!(
    s12_4_6_exit_in_nested_loops,
    "§12.4.6",
    Action,
    "FOR Counters.N0 := 1 TO 3 DO\n  REPEAT\n    EXIT;\n  UNTIL TRUE;\n  END_REPEAT;\n  EXIT;\nEND_FOR;\n"
);
invalid!(s12_4_6_exit_outside_loop, "§12.4.6", Action, "IF Dig_A.Out.Bit0 THEN\n  EXIT;\nEND_IF;\n", ["E0107"]);
