build/gen/rc_pkg.sv
rtl/fp/rc_pipe_out.sv
rtl/fp/rc_fp_add.sv
rtl/fp/rc_fp_mul.sv
rtl/fp/rc_fp_div.sv
rtl/fp/rc_fp_cmp.sv
