//! Error recovery: one run reports every independent error.
use linc_conformance::invalid;

invalid!(three_independent_syntax_errors, "recovery", Action, "TIC_100.SL := REC1.A4 +;\nPIC_004.PV := (1 + ;\nIF Dig_A.Out.Bit3 THEN\n  Dig_B.Out := ) 2;\nEND_IF;\nRecipe.A0 := 1;\n", ["E0010", "E0010", "E0010"]);
invalid!(
    errors_of_every_stage_together,
    "recovery",
    Action,
    "HEAT_PID. SL := 1;\nTIC_100.SL := REC1.A4 *;\nPIC_004.Mode := \"AUTOMATIC\";\nEXIT;\n",
    ["E0004", "E0010", "E0104", "E0107"]
);
invalid!(recovery_inside_condition, "recovery", Action, "IF Recipe.A0 = THEN\n  Recipe.A1 := 1;\nEND_IF;\nWHILE Recipe.A0 < DO\n  Recipe.A1 := Recipe.A1 + 1;\nEND_WHILE;\nRecipe.A2 := SQRT('x');\n", ["E0010", "E0010", "E0112"]);
invalid!(
    checker_keeps_going,
    "recovery",
    Action,
    "PIC_999.PV := 1;\nPIC_004.PVX := 2;\nDig_A.Out.Bit9 := 3;\nPIC_004.PV := 'x';\n",
    ["E0100", "E0101", "E0102", "E0103"]
);
