# Written by bench/tradeoff (tradeoff --plot-only rewrites it from tradeoff.csv).
# Run in this directory: gnuplot tradeoff.gp
if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { term = 'pngcairo' } else { term = 'png' }
$all_0 << EOD
0.02672 0.0526401
0.08307 0.0219962
0.404 0.0244749
0.02538 0.178404
0.08129 0.134232
0.4094 0.123968
0.1366 0.0630069
0.3935 0.0161993
1.953 0.010472
0.1449 0.0571288
0.417 0.0135638
1.977 0.00389021
0.064 1.03552
0.2127 0.0979018
1.427 0.0180732
0.1133 0.290749
0.3401 0.0558505
1.775 0.0128881
0.1632 0.368073
0.5185 0.0651633
2.944 0.0146724
0.001793 0.177435
0.008604 0.177474
0.04215 0.176023
0.2542 0.174937
0.005233 0.136163
0.02106 0.132972
0.1091 0.131363
0.7105 0.130298
0.08052 0.147234
0.2087 0.0554027
0.008125 0.0596597
0.03369 0.0543234
0.1709 0.0528011
1.207 0.0522031
0.02076 0.13007
0.08307 0.123857
0.4686 0.121462
3.026 0.120138
0.4789 0.112953
1.199 0.0251173
0.008357 0.0460995
0.03388 0.0105921
0.174 0.00257184
1.221 0.00063574
0.01981 0.136182
0.07733 0.0295334
0.4374 0.00705136
2.983 0.00173293
0.3727 0.596417
0.9657 0.0989017
0.006472 0.0670127
0.02786 0.0143063
0.1541 0.00340344
1.09 0.000835503
0.01397 0.261251
0.06015 0.042566
0.3739 0.00953545
2.857 0.00229907
0.1913 5.58737
0.5395 0.24322
0.112 0.246481
0.3545 0.0490536
1.78 0.0114218
0.1119 0.197164
0.334 0.0409418
1.796 0.00963905
0.1121 0.154906
0.338 0.0325253
1.843 0.00769165
0.1132 0.0932408
0.342 0.0209143
1.871 0.00503757
0.1164 0.144951
0.3419 0.031174
1.838 0.00741586
0.113 0.290749
0.3534 0.0558505
1.85 0.0128881
0.1563 0.290749
0.5074 0.0558509
2.838 0.0128885
0.01597 0.290748
0.05461 0.05585
0.2299 0.0128883
0.01728 0.0526406
0.05865 0.0219927
0.2695 0.0244718
EOD
$front_0 << EOD
0.001793 0.177435 "pmb"
0.005233 0.136163 "pmb"
0.006472 0.0670127 "corr-none"
0.008125 0.0596597 "lps"
0.008357 0.0460995 "corr-silling"
0.02786 0.0143063 "corr-none"
0.03388 0.0105921 "corr-silling"
0.1541 0.00340344 "corr-none"
0.174 0.00257184 "corr-silling"
1.09 0.000835503 "corr-none"
1.221 0.00063574 "corr-silling"
EOD
set terminal term size 1560,840 noenhanced font ',9'
set output 'mms.png'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 2,3 title 'mms: manufactured static field (L2 error of u)'
set title 'sweep: model'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.02672 0.0526401
0.08307 0.0219962
0.404 0.0244749
e
0.02538 0.178404
0.08129 0.134232
0.4094 0.123968
e
0.1366 0.0630069
0.3935 0.0161993
1.953 0.010472
e
0.1449 0.0571288
0.417 0.0135638
1.977 0.00389021
e
0.064 1.03552
0.2127 0.0979018
1.427 0.0180732
e
0.1133 0.290749
0.3401 0.0558505
1.775 0.0128881
e
0.1632 0.368073
0.5185 0.0651633
2.944 0.0146724
e
set title 'sweep: m'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015', \
     '-' using 1:2 with linespoints pt 10 lw 1.5 title 'corr-none m 1.5', \
     '-' using 1:2 with linespoints pt 11 lw 1.5 title 'corr-none m 2.015', \
     '-' using 1:2 with linespoints pt 12 lw 1.5 title 'corr-none m 4.015'
0.001793 0.177435
0.008604 0.177474
0.04215 0.176023
0.2542 0.174937
e
0.005233 0.136163
0.02106 0.132972
0.1091 0.131363
0.7105 0.130298
e
0.08052 0.147234
0.2087 0.0554027
e
0.008125 0.0596597
0.03369 0.0543234
0.1709 0.0528011
1.207 0.0522031
e
0.02076 0.13007
0.08307 0.123857
0.4686 0.121462
3.026 0.120138
e
0.4789 0.112953
1.199 0.0251173
e
0.008357 0.0460995
0.03388 0.0105921
0.174 0.00257184
1.221 0.00063574
e
0.01981 0.136182
0.07733 0.0295334
0.4374 0.00705136
2.983 0.00173293
e
0.3727 0.596417
0.9657 0.0989017
e
0.006472 0.0670127
0.02786 0.0143063
0.1541 0.00340344
1.09 0.000835503
e
0.01397 0.261251
0.06015 0.042566
0.3739 0.00953545
2.857 0.00229907
e
0.1913 5.58737
0.5395 0.24322
e
set title 'sweep: influence'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.1133 0.290749
0.3401 0.0558505
1.775 0.0128881
e
0.112 0.246481
0.3545 0.0490536
1.78 0.0114218
e
0.1119 0.197164
0.334 0.0409418
1.796 0.00963905
e
0.1121 0.154906
0.338 0.0325253
1.843 0.00769165
e
0.1132 0.0932408
0.342 0.0209143
1.871 0.00503757
e
0.1164 0.144951
0.3419 0.031174
1.838 0.00741586
e
set title 'sweep: precision'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling double'
0.02672 0.0526401
0.08307 0.0219962
0.404 0.0244749
e
0.1366 0.0630069
0.3935 0.0161993
1.953 0.010472
e
0.1133 0.290749
0.3401 0.0558505
1.775 0.0128881
e
set title 'sweep: connectivity'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.1133 0.290749
0.3401 0.0558505
1.775 0.0128881
e
0.113 0.290749
0.3534 0.0558505
1.85 0.0128881
e
0.1563 0.290749
0.5074 0.0558509
2.838 0.0128885
e
set title 'sweep: solver'
plot $all_0 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_0 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb newton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling newton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling adr', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb adr'
0.02672 0.0526401
0.08307 0.0219962
0.404 0.0244749
e
0.1133 0.290749
0.3401 0.0558505
1.775 0.0128881
e
0.01597 0.290748
0.05461 0.05585
0.2299 0.0128883
e
0.01728 0.0526406
0.05865 0.0219927
0.2695 0.0244718
e
unset multiplot
set output
$all_1 << EOD
0.01823 0.0507224
0.09665 0.00819064
0.6202 0.0136069
0.01756 0.241824
0.0955 0.202483
0.6067 0.18231
0.08062 0.0832629
0.4291 0.050905
3.029 0.0341128
0.07946 0.0721965
0.4424 0.0357857
3.012 0.0168654
0.04404 0.525384
0.2709 0.534887
2.331 0.566492
0.0694 0.00644496
0.377 0.0043265
2.848 0.00233881
0.1016 0.00132589
0.6357 0.00168468
4.813 0.00101277
0.002717 0.252515
0.01265 0.238393
0.07026 0.23109
0.416 0.227377
0.005063 0.138175
0.0284 0.135877
0.183 0.134639
1.325 0.133997
0.03658 0.2734
0.2029 0.157715
1.292 0.0984242
0.008593 0.00568258
0.04563 0.0426014
0.2935 0.0678351
1.819 0.0807372
0.01855 0.217227
0.1172 0.185566
0.7478 0.169125
5.282 0.160748
0.1835 0.0471587
0.9846 0.0325057
6.736 0.0253418
0.00892 0.0751876
0.04707 0.038408
0.2933 0.0194306
2.028 0.00977488
0.01855 0.0742747
0.1112 0.0381068
0.738 0.0193113
5.476 0.00972214
0.1417 0.0977401
0.825 0.0515511
6.325 0.026214
0.008063 0.071177
0.05359 0.0364808
0.2936 0.0185076
1.806 0.00931563
0.0148 0.32161
0.09014 0.28303
0.6808 0.266232
5.242 0.258404
0.08936 1.13546
0.5715 1.69532
4.909 1.95389
0.06784 0.0378733
0.3787 0.0185499
2.796 0.00926294
0.007532 0.0715705
0.04222 0.0366709
0.2637 0.0185467
1.709 0.00932489
0.06815 0.0715467
0.3786 0.0361211
2.784 0.0182102
0.007795 0.0722435
0.04269 0.0367681
0.06876 0.0652823
0.3817 0.0330262
2.636 0.0166723
0.006718 0.0721246
0.03851 0.0367579
0.2438 0.0185616
1.656 0.00932757
0.06627 0.0837893
0.3668 0.0428115
2.716 0.0216584
0.007145 0.0720388
0.04144 0.0367397
0.2645 0.0185574
1.695 0.00932651
0.06675 0.0812775
0.3773 0.0413515
2.674 0.0208994
0.007387 0.0721226
0.04092 0.0367575
0.2773 0.0185615
1.874 0.00932755
0.06886 0.00644496
0.3949 0.0043265
2.915 0.00233881
0.08458 0.00644549
0.4229 0.00432679
3.043 0.00233895
0.01587 0.00644847
0.08805 0.00433145
0.5898 0.00234525
0.01363 0.0507186
0.08502 0.00818542
0.5663 0.0136142
EOD
$front_1 << EOD
0.002717 0.252515 "pmb"
0.005063 0.138175 "pmb"
0.006718 0.0721246 "corr-none"
0.007145 0.0720388 "corr-none"
0.007532 0.0715705 "corr-none"
0.008063 0.071177 "corr-none"
0.008593 0.00568258 "lps"
0.08805 0.00433145 "corr-silling"
0.1016 0.00132589 "corr-hourglass"
4.813 0.00101277 "corr-hourglass"
EOD
set terminal term size 1560,1260 noenhanced font ',9'
set output 'vq_uniaxial.png'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 3,3 title 'vq_uniaxial: V-Q uniaxial compression (top displacement)'
set title 'sweep: model'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.01823 0.0507224
0.09665 0.00819064
0.6202 0.0136069
e
0.01756 0.241824
0.0955 0.202483
0.6067 0.18231
e
0.08062 0.0832629
0.4291 0.050905
3.029 0.0341128
e
0.07946 0.0721965
0.4424 0.0357857
3.012 0.0168654
e
0.04404 0.525384
0.2709 0.534887
2.331 0.566492
e
0.0694 0.00644496
0.377 0.0043265
2.848 0.00233881
e
0.1016 0.00132589
0.6357 0.00168468
4.813 0.00101277
e
set title 'sweep: m'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015', \
     '-' using 1:2 with linespoints pt 10 lw 1.5 title 'corr-none m 1.5', \
     '-' using 1:2 with linespoints pt 11 lw 1.5 title 'corr-none m 2.015', \
     '-' using 1:2 with linespoints pt 12 lw 1.5 title 'corr-none m 4.015'
0.002717 0.252515
0.01265 0.238393
0.07026 0.23109
0.416 0.227377
e
0.005063 0.138175
0.0284 0.135877
0.183 0.134639
1.325 0.133997
e
0.03658 0.2734
0.2029 0.157715
1.292 0.0984242
e
0.008593 0.00568258
0.04563 0.0426014
0.2935 0.0678351
1.819 0.0807372
e
0.01855 0.217227
0.1172 0.185566
0.7478 0.169125
5.282 0.160748
e
0.1835 0.0471587
0.9846 0.0325057
6.736 0.0253418
e
0.00892 0.0751876
0.04707 0.038408
0.2933 0.0194306
2.028 0.00977488
e
0.01855 0.0742747
0.1112 0.0381068
0.738 0.0193113
5.476 0.00972214
e
0.1417 0.0977401
0.825 0.0515511
6.325 0.026214
e
0.008063 0.071177
0.05359 0.0364808
0.2936 0.0185076
1.806 0.00931563
e
0.0148 0.32161
0.09014 0.28303
0.6808 0.266232
5.242 0.258404
e
0.08936 1.13546
0.5715 1.69532
4.909 1.95389
e
set title 'sweep: influence'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.0694 0.00644496
0.377 0.0043265
2.848 0.00233881
e
0.06784 0.0378733
0.3787 0.0185499
2.796 0.00926294
e
0.06815 0.0715467
0.3786 0.0361211
2.784 0.0182102
e
0.06876 0.0652823
0.3817 0.0330262
2.636 0.0166723
e
0.06627 0.0837893
0.3668 0.0428115
2.716 0.0216584
e
0.06675 0.0812775
0.3773 0.0413515
2.674 0.0208994
e
set title 'sweep: influence-rf1.5'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.008063 0.071177
0.05359 0.0364808
0.2936 0.0185076
1.806 0.00931563
e
0.007532 0.0715705
0.04222 0.0366709
0.2637 0.0185467
1.709 0.00932489
e
0.007795 0.0722435
0.04269 0.0367681
e
0.006718 0.0721246
0.03851 0.0367579
0.2438 0.0185616
1.656 0.00932757
e
0.007145 0.0720388
0.04144 0.0367397
0.2645 0.0185574
1.695 0.00932651
e
0.007387 0.0721226
0.04092 0.0367575
0.2773 0.0185615
1.874 0.00932755
e
set title 'sweep: precision'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling double'
0.01823 0.0507224
0.09665 0.00819064
0.6202 0.0136069
e
0.08062 0.0832629
0.4291 0.050905
3.029 0.0341128
e
0.0694 0.00644496
0.377 0.0043265
2.848 0.00233881
e
set title 'sweep: connectivity'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.0694 0.00644496
0.377 0.0043265
2.848 0.00233881
e
0.06886 0.00644496
0.3949 0.0043265
2.915 0.00233881
e
0.08458 0.00644549
0.4229 0.00432679
3.043 0.00233895
e
set title 'sweep: solver'
plot $all_1 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_1 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb newton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling newton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling adr', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb adr'
0.01823 0.0507224
0.09665 0.00819064
0.6202 0.0136069
e
0.0694 0.00644496
0.377 0.0043265
2.848 0.00233881
e
0.01587 0.00644847
0.08805 0.00433145
0.5898 0.00234525
e
0.01363 0.0507186
0.08502 0.00818542
0.5663 0.0136142
e
unset multiplot
set output
$all_2 << EOD
0.01718 0.0745181
0.08908 0.025769
0.6033 0.000734461
0.01963 0.251204
0.0932 0.206294
0.628 0.183248
0.08455 0.0672679
0.4405 0.0344628
3.054 0.0174871
0.07952 0.072804
0.4288 0.0373563
2.967 0.0189543
0.04391 0.541587
0.3274 0.55146
2.64 0.584148
0.06668 0.00808447
0.3807 0.00456743
2.914 0.00237018
0.1007 0.00185344
0.6193 0.00137971
5.31 0.000765259
0.002763 0.29338
0.01338 0.281062
0.07765 0.274639
0.5157 0.271356
0.005425 0.0352363
0.03366 0.0325047
0.1813 0.0310583
1.348 0.0303141
0.03749 0.319099
0.2026 0.18725
1.295 0.119641
0.00907 0.0820064
0.0473 0.0420977
0.2812 0.0213322
1.991 0.0107378
0.0192 0.0781639
0.1105 0.0402866
0.733 0.0204733
5.323 0.0103208
0.1724 0.0384446
0.9898 0.0191922
6.452 0.00970004
0.008737 0.0750447
0.04642 0.0384022
0.2922 0.019433
1.943 0.00977594
0.01839 0.0744236
0.1053 0.0381628
0.7464 0.0193272
5.638 0.00972627
0.1408 0.101232
0.8099 0.0518795
6.038 0.0261933
0.06741 0.0363258
0.3887 0.0183265
2.883 0.0092307
0.07432 0.070515
0.3908 0.0359856
2.857 0.0181922
0.06928 0.06458
0.4032 0.0329743
3.115 0.0166761
0.0742 0.0835806
0.3893 0.042791
3.067 0.021657
0.06722 0.0807289
0.3745 0.0412969
2.773 0.0208961
EOD
$front_2 << EOD
0.002763 0.29338 "pmb"
0.005425 0.0352363 "pmb"
0.03366 0.0325047 "pmb"
0.06668 0.00808447 "corr-silling"
0.1007 0.00185344 "corr-hourglass"
0.6033 0.000734461 "pmb"
EOD
set terminal term size 1040,840 noenhanced font ',9'
set output 'vq_isotropic.png'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 2,2 title 'vq_isotropic: V-Q isotropic compression (right-edge displacement)'
set title 'sweep: model'
plot $all_2 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_2 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.01718 0.0745181
0.08908 0.025769
0.6033 0.000734461
e
0.01963 0.251204
0.0932 0.206294
0.628 0.183248
e
0.08455 0.0672679
0.4405 0.0344628
3.054 0.0174871
e
0.07952 0.072804
0.4288 0.0373563
2.967 0.0189543
e
0.04391 0.541587
0.3274 0.55146
2.64 0.584148
e
0.06668 0.00808447
0.3807 0.00456743
2.914 0.00237018
e
0.1007 0.00185344
0.6193 0.00137971
5.31 0.000765259
e
set title 'sweep: m'
plot $all_2 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_2 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015'
0.002763 0.29338
0.01338 0.281062
0.07765 0.274639
0.5157 0.271356
e
0.005425 0.0352363
0.03366 0.0325047
0.1813 0.0310583
1.348 0.0303141
e
0.03749 0.319099
0.2026 0.18725
1.295 0.119641
e
0.00907 0.0820064
0.0473 0.0420977
0.2812 0.0213322
1.991 0.0107378
e
0.0192 0.0781639
0.1105 0.0402866
0.733 0.0204733
5.323 0.0103208
e
0.1724 0.0384446
0.9898 0.0191922
6.452 0.00970004
e
0.008737 0.0750447
0.04642 0.0384022
0.2922 0.019433
1.943 0.00977594
e
0.01839 0.0744236
0.1053 0.0381628
0.7464 0.0193272
5.638 0.00972627
e
0.1408 0.101232
0.8099 0.0518795
6.038 0.0261933
e
set title 'sweep: influence'
plot $all_2 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_2 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.06668 0.00808447
0.3807 0.00456743
2.914 0.00237018
e
0.06741 0.0363258
0.3887 0.0183265
2.883 0.0092307
e
0.07432 0.070515
0.3908 0.0359856
2.857 0.0181922
e
0.06928 0.06458
0.4032 0.0329743
3.115 0.0166761
e
0.0742 0.0835806
0.3893 0.042791
3.067 0.021657
e
0.06722 0.0807289
0.3745 0.0412969
2.773 0.0208961
e
set title 'sweep: precision'
plot $all_2 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_2 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling double'
0.01718 0.0745181
0.08908 0.025769
0.6033 0.000734461
e
0.08455 0.0672679
0.4405 0.0344628
3.054 0.0174871
e
0.06668 0.00808447
0.3807 0.00456743
2.914 0.00237018
e
unset multiplot
set output
$all_3 << EOD
0.01825 0.0966072
0.09234 0.0531654
0.6247 0.0315884
0.01808 0.236483
0.09276 0.195019
0.6435 0.174474
0.08113 0.0248073
0.4282 0.00470698
2.966 0.019898
0.0785 0.0675591
0.4302 0.0371671
3.108 0.0213948
0.04356 0.750117
0.2737 0.704929
2.386 0.697433
0.06969 0.0381945
0.3761 0.0220039
2.859 0.0116292
0.1004 0.0535838
0.6628 0.0302717
4.902 0.0158957
0.002565 0.380077
0.01242 0.377917
0.06579 0.376641
0.4064 0.375949
0.005196 0.50843
0.02862 0.510967
0.1869 0.512607
1.282 0.513532
0.03576 0.285843
0.1982 0.188191
1.282 0.13995
0.00903 0.19554
0.04904 0.171888
0.3235 0.159429
1.819 0.153008
0.01801 0.460649
0.0998 0.50993
0.7533 0.535074
5.365 0.547806
0.1733 0.0104132
0.9796 0.0137034
6.537 0.0259669
0.008861 0.0685613
0.05281 0.0346713
0.2867 0.0174672
1.828 0.00877049
0.01736 0.075287
0.1049 0.0382263
0.7288 0.0192779
5.217 0.00968296
0.1406 0.179296
0.8333 0.097721
6.003 0.050799
0.007196 0.0605786
0.03936 0.0301953
0.2654 0.0151451
1.711 0.00757736
0.01338 0.267956
0.09128 0.258753
0.6429 0.259484
4.787 0.243291
0.08884 1.55055
0.5639 1.77841
4.698 1.69774
0.06503 0.024992
0.3769 0.011381
2.751 0.00549853
0.00729 0.0601528
0.04081 0.0301825
0.2747 0.015124
1.733 0.00757202
0.06638 0.0701639
0.3694 0.0352164
2.751 0.0176897
0.00691 0.0598209
0.039 0.0300272
0.06815 0.06402
0.3873 0.0321181
2.758 0.016143
0.007201 0.060652
0.04074 0.0303153
0.2846 0.0151651
1.809 0.00758382
0.07484 0.0841219
0.3756 0.0426694
2.733 0.0215079
0.007122 0.061316
0.03954 0.0305339
0.2594 0.0152305
1.75 0.00760227
0.0667 0.0829429
0.3975 0.0419844
2.728 0.0211519
0.007652 0.0606604
0.04053 0.0303182
0.2569 0.015166
1.954 0.00758407
0.07293 0.0381945
0.3733 0.0220039
2.839 0.0116292
0.07806 0.0381945
0.4109 0.0220039
2.824 0.0116292
EOD
$front_3 << EOD
0.002565 0.380077 "pmb"
0.00691 0.0598209 "corr-none"
0.039 0.0300272 "corr-none"
0.06503 0.024992 "corr-silling"
0.08113 0.0248073 "lps"
0.1733 0.0104132 "lps"
0.4282 0.00470698 "lps"
EOD
set terminal term size 1560,840 noenhanced font ',9'
set output 'vq_shear.png'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 2,3 title 'vq_shear: V-Q simple shear (top displacement)'
set title 'sweep: model'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.01825 0.0966072
0.09234 0.0531654
0.6247 0.0315884
e
0.01808 0.236483
0.09276 0.195019
0.6435 0.174474
e
0.08113 0.0248073
0.4282 0.00470698
2.966 0.019898
e
0.0785 0.0675591
0.4302 0.0371671
3.108 0.0213948
e
0.04356 0.750117
0.2737 0.704929
2.386 0.697433
e
0.06969 0.0381945
0.3761 0.0220039
2.859 0.0116292
e
0.1004 0.0535838
0.6628 0.0302717
4.902 0.0158957
e
set title 'sweep: m'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015', \
     '-' using 1:2 with linespoints pt 10 lw 1.5 title 'corr-none m 1.5', \
     '-' using 1:2 with linespoints pt 11 lw 1.5 title 'corr-none m 2.015', \
     '-' using 1:2 with linespoints pt 12 lw 1.5 title 'corr-none m 4.015'
0.002565 0.380077
0.01242 0.377917
0.06579 0.376641
0.4064 0.375949
e
0.005196 0.50843
0.02862 0.510967
0.1869 0.512607
1.282 0.513532
e
0.03576 0.285843
0.1982 0.188191
1.282 0.13995
e
0.00903 0.19554
0.04904 0.171888
0.3235 0.159429
1.819 0.153008
e
0.01801 0.460649
0.0998 0.50993
0.7533 0.535074
5.365 0.547806
e
0.1733 0.0104132
0.9796 0.0137034
6.537 0.0259669
e
0.008861 0.0685613
0.05281 0.0346713
0.2867 0.0174672
1.828 0.00877049
e
0.01736 0.075287
0.1049 0.0382263
0.7288 0.0192779
5.217 0.00968296
e
0.1406 0.179296
0.8333 0.097721
6.003 0.050799
e
0.007196 0.0605786
0.03936 0.0301953
0.2654 0.0151451
1.711 0.00757736
e
0.01338 0.267956
0.09128 0.258753
0.6429 0.259484
4.787 0.243291
e
0.08884 1.55055
0.5639 1.77841
4.698 1.69774
e
set title 'sweep: influence'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.06969 0.0381945
0.3761 0.0220039
2.859 0.0116292
e
0.06503 0.024992
0.3769 0.011381
2.751 0.00549853
e
0.06638 0.0701639
0.3694 0.0352164
2.751 0.0176897
e
0.06815 0.06402
0.3873 0.0321181
2.758 0.016143
e
0.07484 0.0841219
0.3756 0.0426694
2.733 0.0215079
e
0.0667 0.0829429
0.3975 0.0419844
2.728 0.0211519
e
set title 'sweep: influence-rf1.5'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.007196 0.0605786
0.03936 0.0301953
0.2654 0.0151451
1.711 0.00757736
e
0.00729 0.0601528
0.04081 0.0301825
0.2747 0.015124
1.733 0.00757202
e
0.00691 0.0598209
0.039 0.0300272
e
0.007201 0.060652
0.04074 0.0303153
0.2846 0.0151651
1.809 0.00758382
e
0.007122 0.061316
0.03954 0.0305339
0.2594 0.0152305
1.75 0.00760227
e
0.007652 0.0606604
0.04053 0.0303182
0.2569 0.015166
1.954 0.00758407
e
set title 'sweep: precision'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling double'
0.01825 0.0966072
0.09234 0.0531654
0.6247 0.0315884
e
0.08113 0.0248073
0.4282 0.00470698
2.966 0.019898
e
0.06969 0.0381945
0.3761 0.0220039
2.859 0.0116292
e
set title 'sweep: connectivity'
plot $all_3 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_3 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.06969 0.0381945
0.3761 0.0220039
2.859 0.0116292
e
0.07293 0.0381945
0.3733 0.0220039
2.839 0.0116292
e
0.07806 0.0381945
0.4109 0.0220039
2.824 0.0116292
e
unset multiplot
set output
$all_4 << EOD
0.003161 0.0224708
0.01796 0.00142435
0.1198 0.00863098
0.8817 0.0135493
0.003592 0.111023
0.02035 0.091093
0.1425 0.0815329
1.011 0.0768498
0.004768 0.0762345
0.02976 0.0412642
0.205 0.0236726
1.564 0.0147539
0.004965 0.0627701
0.03048 0.0312362
0.2189 0.015349
1.646 0.00730116
0.002068 0.00432525
0.009723 0.00126442
0.06233 0.000343664
0.5045 8.90932e-05
0.003393 0.00286452
0.01806 0.000956629
0.1178 0.000271154
0.9153 7.16783e-05
0.004534 0.00279669
0.02434 0.00094935
0.1592 0.0002704
1.208 7.21053e-05
0.001933 0.104836
0.01156 0.120046
0.07665 0.127525
0.563 0.131232
0.001797 0.0605541
0.01041 0.067584
0.07044 0.0709282
0.5344 0.0725632
0.003999 0.0755543
0.02197 0.0458173
0.1429 0.0318658
1.009 0.0250933
0.002858 0.00817292
0.0171 0.0102474
0.1236 0.0195711
0.9894 0.024276
0.002856 0.118798
0.02018 0.0889353
0.1312 0.0737445
0.959 0.0660209
0.006032 0.0913111
0.03869 0.0488791
0.2633 0.0277429
1.98 0.0170456
0.002479 0.000853876
0.01376 0.000234428
0.09532 6.14019e-05
0.7591 1.57136e-05
0.002314 0.00192317
0.0123 0.000593244
0.08234 0.000162166
0.6332 4.24254e-05
0.005036 0.00389633
0.02491 0.00145315
0.1534 0.000430168
1.159 0.000117084
0.003355 0.00255619
0.01919 0.00087677
0.1264 0.000248026
0.9631 6.52591e-05
0.004139 0.00244963
0.02107 0.000789558
0.1365 0.000218958
1.053 5.75447e-05
0.003539 0.00201346
0.02149 0.0006222
0.1467 0.000171478
1.154 4.50065e-05
0.004132 0.00150371
0.02479 0.000447652
0.1774 0.000120797
1.466 3.13575e-05
0.003713 0.00203879
0.02276 0.000625753
0.1521 0.000172078
1.189 4.50038e-05
0.003249 0.00286452
0.01825 0.000956629
0.1148 0.000271154
0.914 7.16783e-05
0.003862 0.0028645
0.02296 0.000956626
0.1421 0.000271153
1.098 7.16781e-05
0.00684 0.00446583
0.04605 0.00137769
0.3575 0.000377473
3.28 9.84119e-05
0.004597 0.00412922
0.02743 0.00129305
0.198 0.000356063
1.663 9.3103e-05
0.003041 0.00182028
0.01619 0.000704797
0.1001 0.000207752
0.732 5.56883e-05
0.006233 0.0233922
0.04387 0.00166263
0.3348 0.0085701
2.707 0.0135337
0.00387 0.023204
0.02532 0.0016149
0.1857 0.00858241
1.439 0.0135368
0.002471 0.0219287
0.01392 0.00128135
0.08983 0.00866764
0.6414 0.0135586
0.003219 0.00286452
0.01748 0.000956629
0.1161 0.000271154
0.8884 7.16783e-05
0.002678 0.0224708
0.01578 0.00142435
0.1055 0.00863098
0.7603 0.0135493
EOD
$front_4 << EOD
0.001797 0.0605541 "pmb"
0.002068 0.00432525 "corr-none"
0.002314 0.00192317 "corr-silling"
0.002479 0.000853876 "corr-silling"
0.0123 0.000593244 "corr-silling"
0.01376 0.000234428 "corr-silling"
0.08234 0.000162166 "corr-silling"
0.09532 6.14019e-05 "corr-silling"
0.6332 4.24254e-05 "corr-silling"
0.7591 1.57136e-05 "corr-silling"
EOD
set terminal term size 1560,1260 noenhanced font ',9'
set output 'wave.png'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 3,3 title 'wave: standing wave in a bar (frequency)'
set title 'sweep: model'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.003161 0.0224708
0.01796 0.00142435
0.1198 0.00863098
0.8817 0.0135493
e
0.003592 0.111023
0.02035 0.091093
0.1425 0.0815329
1.011 0.0768498
e
0.004768 0.0762345
0.02976 0.0412642
0.205 0.0236726
1.564 0.0147539
e
0.004965 0.0627701
0.03048 0.0312362
0.2189 0.015349
1.646 0.00730116
e
0.002068 0.00432525
0.009723 0.00126442
0.06233 0.000343664
0.5045 8.90932e-05
e
0.003393 0.00286452
0.01806 0.000956629
0.1178 0.000271154
0.9153 7.16783e-05
e
0.004534 0.00279669
0.02434 0.00094935
0.1592 0.0002704
1.208 7.21053e-05
e
set title 'sweep: m'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015'
0.001933 0.104836
0.01156 0.120046
0.07665 0.127525
0.563 0.131232
e
0.001797 0.0605541
0.01041 0.067584
0.07044 0.0709282
0.5344 0.0725632
e
0.003999 0.0755543
0.02197 0.0458173
0.1429 0.0318658
1.009 0.0250933
e
0.002858 0.00817292
0.0171 0.0102474
0.1236 0.0195711
0.9894 0.024276
e
0.002856 0.118798
0.02018 0.0889353
0.1312 0.0737445
0.959 0.0660209
e
0.006032 0.0913111
0.03869 0.0488791
0.2633 0.0277429
1.98 0.0170456
e
0.002479 0.000853876
0.01376 0.000234428
0.09532 6.14019e-05
0.7591 1.57136e-05
e
0.002314 0.00192317
0.0123 0.000593244
0.08234 0.000162166
0.6332 4.24254e-05
e
0.005036 0.00389633
0.02491 0.00145315
0.1534 0.000430168
1.159 0.000117084
e
set title 'sweep: influence'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.003393 0.00286452
0.01806 0.000956629
0.1178 0.000271154
0.9153 7.16783e-05
e
0.003355 0.00255619
0.01919 0.00087677
0.1264 0.000248026
0.9631 6.52591e-05
e
0.004139 0.00244963
0.02107 0.000789558
0.1365 0.000218958
1.053 5.75447e-05
e
0.003539 0.00201346
0.02149 0.0006222
0.1467 0.000171478
1.154 4.50065e-05
e
0.004132 0.00150371
0.02479 0.000447652
0.1774 0.000120797
1.466 3.13575e-05
e
0.003713 0.00203879
0.02276 0.000625753
0.1521 0.000172078
1.189 4.50038e-05
e
set title 'sweep: precision'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling double'
0.003161 0.0224708
0.01796 0.00142435
0.1198 0.00863098
0.8817 0.0135493
e
0.004768 0.0762345
0.02976 0.0412642
0.205 0.0236726
1.564 0.0147539
e
0.003393 0.00286452
0.01806 0.000956629
0.1178 0.000271154
0.9153 7.16783e-05
e
set title 'sweep: connectivity'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.003393 0.00286452
0.01806 0.000956629
0.1178 0.000271154
0.9153 7.16783e-05
e
0.003249 0.00286452
0.01825 0.000956629
0.1148 0.000271154
0.914 7.16783e-05
e
0.003862 0.0028645
0.02296 0.000956626
0.1421 0.000271153
1.098 7.16781e-05
e
set title 'sweep: dt'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb safety 0.8', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling safety 0.8', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling safety 0.2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'corr-silling safety 0.4', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-silling safety 1', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'pmb safety 0.2', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'pmb safety 0.4', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'pmb safety 1'
0.003161 0.0224708
0.01796 0.00142435
0.1198 0.00863098
0.8817 0.0135493
e
0.003393 0.00286452
0.01806 0.000956629
0.1178 0.000271154
0.9153 7.16783e-05
e
0.00684 0.00446583
0.04605 0.00137769
0.3575 0.000377473
3.28 9.84119e-05
e
0.004597 0.00412922
0.02743 0.00129305
0.198 0.000356063
1.663 9.3103e-05
e
0.003041 0.00182028
0.01619 0.000704797
0.1001 0.000207752
0.732 5.56883e-05
e
0.006233 0.0233922
0.04387 0.00166263
0.3348 0.0085701
2.707 0.0135337
e
0.00387 0.023204
0.02532 0.0016149
0.1857 0.00858241
1.439 0.0135368
e
0.002471 0.0219287
0.01392 0.00128135
0.08983 0.00866764
0.6414 0.0135586
e
set title 'sweep: order'
plot $all_4 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_4 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb morton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling morton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling lattice', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb lattice'
0.003161 0.0224708
0.01796 0.00142435
0.1198 0.00863098
0.8817 0.0135493
e
0.003393 0.00286452
0.01806 0.000956629
0.1178 0.000271154
0.9153 7.16783e-05
e
0.003219 0.00286452
0.01748 0.000956629
0.1161 0.000271154
0.8884 7.16783e-05
e
0.002678 0.0224708
0.01578 0.00142435
0.1055 0.00863098
0.7603 0.0135493
e
unset multiplot
set output
$all_5 << EOD
0.06509 0.390178
0.3843 0.339095
2.535 0.244481
0.06355 0.308139
0.3748 0.196165
2.555 0.0824364
0.2858 0.533681
1.677 0.420568
12.46 0.320695
0.2928 0.51248
1.669 0.412628
12.13 0.303488
0.0869 0.0622503
0.5978 0.292488
5.681 0.687491
0.1277 0.415254
0.8163 0.279536
7.082 0.21749
0.3817 0.384284
2.655 0.276365
22.65 0.216883
0.009487 0.466931
0.04916 0.406714
0.3102 0.330688
1.976 0.242284
0.02111 0.44057
0.1286 0.342947
0.7725 0.238028
5.408 0.104971
0.1297 0.145724
0.7694 0.146552
0.03061 0.375309
0.1913 0.255415
1.253 0.125387
7.324 0.029021
0.06647 0.506762
0.4105 0.395818
3.218 0.269266
24.63 0.11095
0.6327 0.532192
3.803 0.426641
0.01644 0.350017
0.1047 0.292287
0.7006 0.177294
4.523 0.0517944
0.03528 0.378525
0.2219 0.300901
1.878 0.200412
13.33 0.0563681
0.264 0.336706
1.765 0.27608
0.1248 0.392877
0.7759 0.264265
6.291 0.206586
0.1219 0.367349
0.7648 0.254476
6.224 0.190857
0.1258 0.335052
0.7827 0.244522
6.464 0.185088
0.1276 0.32135
0.7788 0.263281
6.457 0.162179
0.1307 0.34011
0.8184 0.248308
7.084 0.173915
0.1299 0.415254
0.821 0.279536
6.662 0.21749
0.3068 0.415654
2.047 0.280186
17.4 0.218248
0.0248 0.415252
0.1729 0.279532
1.173 0.217483
0.02491 0.390178
0.1694 0.339099
1.297 0.244488
EOD
$front_5 << EOD
0.009487 0.466931 "pmb"
0.01644 0.350017 "corr-silling"
0.06355 0.308139 "pmb-pv"
0.0869 0.0622503 "corr-none"
4.523 0.0517944 "corr-silling"
7.324 0.029021 "lps"
EOD
set terminal term size 1560,840 noenhanced font ',9'
set output 'hole.png'
set logscale xy
set grid
set format x '%g'
set format y '%g'
set key outside right top Left reverse samplen 2 spacing 0.9 font ',8'
set xlabel 'cost: CPU time [s], 1 thread'
set ylabel 'relative error'
set multiplot layout 2,3 title 'hole: plate with a hole, d/W = 0.2 (stress concentration 3.14)'
set title 'sweep: model'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb-pv', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'lps', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps-pv', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'corr-none', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'corr-silling', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-hourglass'
0.06509 0.390178
0.3843 0.339095
2.535 0.244481
e
0.06355 0.308139
0.3748 0.196165
2.555 0.0824364
e
0.2858 0.533681
1.677 0.420568
12.46 0.320695
e
0.2928 0.51248
1.669 0.412628
12.13 0.303488
e
0.0869 0.0622503
0.5978 0.292488
5.681 0.687491
e
0.1277 0.415254
0.8163 0.279536
7.082 0.21749
e
0.3817 0.384284
2.655 0.276365
22.65 0.216883
e
set title 'sweep: m'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb m 1.5', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'pmb m 2.015', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'pmb m 4.015', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'lps m 1.5', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'lps m 2.015', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'lps m 4.015', \
     '-' using 1:2 with linespoints pt 7 lw 1.5 title 'corr-silling m 1.5', \
     '-' using 1:2 with linespoints pt 8 lw 1.5 title 'corr-silling m 2.015', \
     '-' using 1:2 with linespoints pt 9 lw 1.5 title 'corr-silling m 4.015'
0.009487 0.466931
0.04916 0.406714
0.3102 0.330688
1.976 0.242284
e
0.02111 0.44057
0.1286 0.342947
0.7725 0.238028
5.408 0.104971
e
0.1297 0.145724
0.7694 0.146552
e
0.03061 0.375309
0.1913 0.255415
1.253 0.125387
7.324 0.029021
e
0.06647 0.506762
0.4105 0.395818
3.218 0.269266
24.63 0.11095
e
0.6327 0.532192
3.803 0.426641
e
0.01644 0.350017
0.1047 0.292287
0.7006 0.177294
4.523 0.0517944
e
0.03528 0.378525
0.2219 0.300901
1.878 0.200412
13.33 0.0563681
e
0.264 0.336706
1.765 0.27608
e
set title 'sweep: influence'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'constant', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'inv_r', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'inv_r2', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'linear', \
     '-' using 1:2 with linespoints pt 5 lw 1.5 title 'cubic', \
     '-' using 1:2 with linespoints pt 6 lw 1.5 title 'gaussian'
0.1277 0.415254
0.8163 0.279536
7.082 0.21749
e
0.1248 0.392877
0.7759 0.264265
6.291 0.206586
e
0.1219 0.367349
0.7648 0.254476
6.224 0.190857
e
0.1258 0.335052
0.7827 0.244522
6.464 0.185088
e
0.1276 0.32135
0.7788 0.263281
6.457 0.162179
e
0.1307 0.34011
0.8184 0.248308
7.084 0.173915
e
set title 'sweep: precision'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb double', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'lps double', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling double'
0.06509 0.390178
0.3843 0.339095
2.535 0.244481
e
0.2858 0.533681
1.677 0.420568
12.46 0.320695
e
0.1277 0.415254
0.8163 0.279536
7.082 0.21749
e
set title 'sweep: connectivity'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'tl', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'semi_tl', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'ul'
0.1277 0.415254
0.8163 0.279536
7.082 0.21749
e
0.1299 0.415254
0.821 0.279536
6.662 0.21749
e
0.3068 0.415654
2.047 0.280186
17.4 0.218248
e
set title 'sweep: solver'
plot $all_5 using 1:2 with points pt 7 ps 0.4 lc rgb '#c8c8c8' notitle, \
     $front_5 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     '-' using 1:2 with linespoints pt 1 lw 1.5 title 'pmb newton', \
     '-' using 1:2 with linespoints pt 2 lw 1.5 title 'corr-silling newton', \
     '-' using 1:2 with linespoints pt 3 lw 1.5 title 'corr-silling adr', \
     '-' using 1:2 with linespoints pt 4 lw 1.5 title 'pmb adr'
0.06509 0.390178
0.3843 0.339095
2.535 0.244481
e
0.1277 0.415254
0.8163 0.279536
7.082 0.21749
e
0.0248 0.415252
0.1729 0.279532
1.173 0.217483
e
0.02491 0.390178
0.1694 0.339099
1.297 0.244488
e
unset multiplot
set output
