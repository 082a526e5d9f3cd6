## nexys_video.xdc: pins and timing of rc_nexys_video (fpga/xilinx/rc_nexys_video.sv) on the
## Digilent Nexys Video (XC7A200T-1SBG484C). Read by fpga/xilinx/build.tcl.
##
## Sites, banks and I/O standards are those of Digilent's Nexys Video master XDC (Rev. A) and
## reference manual; the names in brackets are the master XDC's (schematic) names. The board powers
## its banks at different voltages (as the master XDC's I/O standards show), so the I/O standard
## follows the bank, not LVCMOS33 for all:
##   bank 13: 2.5 V (the LEDs)             bank 14: 3.3 V (USB-UART, configuration)
##   bank 34: 3.3 V (the 100 MHz clock)    bank 35: 1.5 V (the CPU RESET button)
##   bank 16: 1.2 V (the push buttons)
## Untested here: no Vivado on the machine this was written on (docs/fpga.md).

## Configuration bank: 3.3 V (Nexys Video), for Vivado's CFGBVS/CONFIG_VOLTAGE DRCs.
set_property CFGBVS VCCO [current_design]
set_property CONFIG_VOLTAGE 3.3 [current_design]
set_property BITSTREAM.GENERAL.COMPRESS TRUE [current_design]

## 100 MHz oscillator [sysclk], IO_L13P_T2_MRCC_34 (a clock-capable pin).
set_property -dict {PACKAGE_PIN R4 IOSTANDARD LVCMOS33} [get_ports clk_i]
create_clock -name sys_clk -period 10.000 -waveform {0.000 5.000} [get_ports clk_i]

## CPU RESET button [cpu_resetn], IO_L12N_T1_MRCC_35, low while pressed.
set_property -dict {PACKAGE_PIN G4 IOSTANDARD LVCMOS15} [get_ports cpu_rst_ni]

## Centre button [btnc], IO_L20N_T3_16, high while pressed.
set_property -dict {PACKAGE_PIN B22 IOSTANDARD LVCMOS12} [get_ports btnc_i]

## LEDs LD0 .. LD7 [led[0] .. led[7]], bank 13.
set_property -dict {PACKAGE_PIN T14 IOSTANDARD LVCMOS25} [get_ports {led_o[0]}]
set_property -dict {PACKAGE_PIN T15 IOSTANDARD LVCMOS25} [get_ports {led_o[1]}]
set_property -dict {PACKAGE_PIN T16 IOSTANDARD LVCMOS25} [get_ports {led_o[2]}]
set_property -dict {PACKAGE_PIN U16 IOSTANDARD LVCMOS25} [get_ports {led_o[3]}]
set_property -dict {PACKAGE_PIN V15 IOSTANDARD LVCMOS25} [get_ports {led_o[4]}]
set_property -dict {PACKAGE_PIN W16 IOSTANDARD LVCMOS25} [get_ports {led_o[5]}]
set_property -dict {PACKAGE_PIN W15 IOSTANDARD LVCMOS25} [get_ports {led_o[6]}]
set_property -dict {PACKAGE_PIN Y13 IOSTANDARD LVCMOS25} [get_ports {led_o[7]}]

## USB-UART bridge, bank 14. The master XDC names the lines from the host's side:
## [uart_tx_in] V18, IO_L14P_T2_SRCC_14: host -> FPGA (our receiver input);
## [uart_rx_out] AA19, IO_L15P_T2_DQS_RDWR_B_14: FPGA -> host (our transmitter output).
## The pull-up keeps the receiver's line idle (high) while the bridge is unpowered (no USB cable).
set_property -dict {PACKAGE_PIN V18 IOSTANDARD LVCMOS33 PULLUP TRUE} [get_ports uart_rx_i]
set_property -dict {PACKAGE_PIN AA19 IOSTANDARD LVCMOS33} [get_ports uart_tx_o]

## Asynchronous I/O. The reset button's release, BTNC and the UART input pass two-flip-flop
## synchronisers (rc_nexys_video, rc_uart_rx); the LEDs and the UART output come from flip-flops
## and change far slower than the clock. None of them has a timing relation to sys_clk.
set_false_path -from [get_ports {cpu_rst_ni btnc_i uart_rx_i}]
set_false_path -to [get_ports {led_o[*] uart_tx_o}]
