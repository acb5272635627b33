//! §12.6 function table: calls checked against the stdlib signatures.
use linc_conformance::{invalid, valid};

valid!(s12_6_convert_functions, "§12.6 Convert", Action, "Recipe.A0 := ABS(Recipe.A1) + FLOAT(Recipe.N0);\nRecipe.N0 := ROUND(Recipe.A1) + TRUNC(2.7);\nTx_Value := FORMAT(\"04X\", Raw1.I2);\nDig_A.Out.Bit0 := IS_VALID(\"U\", ' -4789');\n");
valid!(s12_6_scan_example_completed, "§12.6 Convert", Action, "Setpoint := SCAN(\"X\", MID(Raw1.Rx_Value, 4, 10));\n");
invalid!(
    s12_6_scan_example_as_printed,
    "§12.6 Convert",
    Action,
    "Setpoint := SCAN(\"X\", MID(Raw1.Rx_Value, 4, 10);\n",
    ["E0010"]
);
valid!(s12_6_numeric_functions, "§12.6 Numeric", Action, "Recipe.A0 := ACOS(0.5) + ASIN(0.5) + ATAN2(1, 2) + COS(1) + DEG(1) + EXP(1);\nRecipe.A1 := LN(2) + LOG(100) + RAD(90) + SIN(1) + SQRT(2) + TAN(1);\n");
valid!(s12_6_random, "§12.6 Random", Action, "Recipe.A0 := RANDOM(10);\n");
valid!(s12_6_selectors, "§12.6 Selector", Action, "Recipe.A0 := AVG(1, 2, 3, 4);\nRecipe.A1 := MAX(Recipe.A2, 5) + MIN(1, 2, 3);\nRecipe.N0 := SWITCH(1, 2, Recipe.N1);\n");
invalid!(s12_6_avg_needs_two_arguments, "§12.6 Selector", Action, "Recipe.A0 := AVG(Recipe.A1);\n", ["E0111"]);
valid!(s12_6_string_basics, "§12.6 String", Action, "Buffer1 := CONCAT(LEFT(Buffer1, 3), RIGHT(Buffer1, 2));\nBuffer1 := INSERT(DELETE(Buffer1, 2, 1), 'ab', 1);\nBuffer1 := REPLACE(Buffer1, 'x', 1, 2);\nRecipe.N0 := FIND('ABACA', 'A', 2) + FIND('ABACA', 'A') + LEN(Buffer1) + STRCOMP('aa', 'ab');\nBuffer1 := DELIMIT('a+b+c', '+', 2);\nBuffer1 := JUSTIFY_LEFT(Buffer1, 10);\nBuffer1 := JUSTIFY_RIGHT(TRIM(Buffer1), 10);\nBuffer1 := JUSTIFY_CENTRE(LTRIM(RTRIM(Buffer1)), 10);\nBuffer1 := UCASE(LCASE(Buffer1));\nBuffer1 := CONCAT(STRING(3, '*'), SPACE(2));\nBuffer1 := PURGE('abcdabcde', 'bd');\nDig_A.Out.Bit0 := EQUAL(Buffer1, 'x');\n");
valid!(s12_6_date_and_time_example_completed, "§12.6 Date", Action, "Buffer1 := DATEANDTIMENOW( );\nBuffer1 := CONCAT(CONCAT(MID(Buffer1,3,4), LEFT(Buffer1,3)), MID(Buffer1,2,9));\nBuffer1 := DATEANDTIMENOW(1);\n");
invalid!(
    s12_6_date_example_as_printed,
    "§12.6 Date",
    Action,
    "Buffer1 := CONCAT(CONCAT(MID(Buffer1,3,4), LEFT(Buffer1,3)), MID(Buffer1,2,9);\n",
    ["E0010"]
);
valid!(s12_6_extract_replace, "§12.6 Extract/Replace", Action, "Dig_A.Out.Bit0 := EXTRACT_BOOL(Buffer1, 1, 7);\nRecipe.N0 := EXTRACT_INT8(Buffer1, 1) + EXTRACT_UINT8(Buffer1, 2) + EXTRACT_INT16(Buffer1, 1, 1) + EXTRACT_UINT16(Buffer1, 1, 0) + EXTRACT_INT32(Buffer1, 1, 3);\nRecipe.A0 := EXTRACT_REAL(Buffer1, 1, 2);\nBuffer1 := REPLACE_BOOL(Buffer1, 1, 0, TRUE);\nBuffer1 := REPLACE_INT8(REPLACE_UINT8(Buffer1, 1, 200), 2, -3);\nBuffer1 := REPLACE_INT16(REPLACE_UINT16(Buffer1, 1, 65535, 1), 3, -2, 0);\nBuffer1 := REPLACE_INT32(REPLACE_REAL(Buffer1, 1, 3.5, 3), 5, 7, 2);\n");
valid!(s12_6_bit_functions, "§12.6 Bit", Action, "Recipe.N0 := BIT_INVERT(Recipe.N1) + SHL8(1, 3) + SHL16(1, 3) + SHL32(1, 3) + SHR8(128, 3) + SHR16(1, 3) + SHR32(1, 3);\nRecipe.N1 := ROL8(1, 3) + ROL16(1, 3) + ROL32(1, 3) + ROR8(1, 3) + ROR16(1, 3) + ROR32(1, 3);\n");
valid!(
    s12_6_1_crc_example,
    "§12.6.1",
    Action,
    "Recipe.N0 := CRC('123456789',1,16#8005,16#FFFF);\nRecipe.N1 := BCC(Buffer1, 0, 0);\n"
);
valid!(s12_6_2_find_examples, "§12.6.2", Action, "Recipe.N0 := FIND('ABACA','A',2);\nRecipe.N1 := FIND('ABACABA','AB',2);\nRecipe.N2 := FIND('AAAAA', 'AA', -1);\nRecipe.N3 := FIND('AAAAA', 'A', -1);\nRecipe.N4 := FIND('AAAAA','',-1);\n");
valid!(s12_6_3_format_examples, "§12.6.3", Action, "Tx_Value := FORMAT(\"5I\",Value);\nTx_Value := FORMAT(\"05I\",Value);\nTx_Value := FORMAT(\"3I!\",Value);\nTx_Value := FORMAT(\"06x\",Value);\nTx_Value := FORMAT(\"08B\",Value);\nTx_Value := FORMAT(\"04O\",Value);\nTx_Value := FORMAT(\"6.2F\",RealVal);\nTx_Value := FORMAT(\"10.2E\",RealVal);\nTx_Value := FORMAT(\"C\",Value);\nTx_Value := FORMAT(\"T.\",Value);\nTx_Value := FORMAT(\"TP\",Value);\nTx_Value := FORMAT(\"D\",Value);\nTx_Value := FORMAT(\"DP\",Value);\n");
valid!(s12_6_3_scan_examples, "§12.6.3", Action, "Value := SCAN(\"I\", '  4789');\nValue := SCAN(\"3I\", '-4789');\nValue := SCAN(\"2U\", '4789');\nValue := SCAN(\"X\", 'FF');\nValue := SCAN(\"B\", ' 1111111111');\nRealVal := SCAN(\"F\", ' -1.456E-2');\nRealVal := SCAN(\"G\", ' -1.456E-2');\nValue := SCAN(\"C\", 'B');\nValue := SCAN(\"T\", '14:27:30');\nValue := SCAN(\"DP\", '15/01/70');\n");
invalid!(s12_6_unknown_function, "§12.6", Action, "Recipe.A0 := SQR(2);\n", ["E0110"]);
invalid!(s12_6_wrong_argument_count, "§12.6", Action, "Buffer1 := MID(Buffer1, 2);\n", ["E0111"]);
invalid!(s12_6_wrong_argument_type, "§12.6", Action, "Recipe.N0 := LEN(Recipe.A0);\n", ["E0112"]);
invalid!(s12_6_string_where_number_expected, "§12.6", Action, "Recipe.A0 := SQRT('4');\n", ["E0112"]);
valid!(s12_6_function_names_ignore_case, "§12", Action, "Recipe.A0 := sqrt(Recipe.A1) + Abs(-2);\n");
valid!(s12_6_real_argument_for_integer_parameter, "§12.6", Action, "Buffer1 := LEFT(Buffer1, Recipe.A0);\n");
